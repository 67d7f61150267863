#pragma once
// CRC-24Q (Galileo OS SIS ICD 4.1.2, as RTCM 3 and GPS CNAV use it): generator
// x^24 + x^23 + x^18 + x^17 + x^14 + x^11 + x^10 + x^7 + x^6 + x^5 + x^4 + x^3 + x + 1, zero
// initial value, no reflection, no final inversion, over a bit sequence sent first bit first.
#include <cstdint>
#include <span>

namespace deepnav::galileo {

/// CRC-24Q of `bits` (one bit, 0 or 1, per element), 24 bits in the low end of the result.
std::uint32_t crc24q(std::span<const std::uint8_t> bits);

}  // namespace deepnav::galileo
