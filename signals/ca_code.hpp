#pragma once
// GPS L1 C/A Gold codes (IS-GPS-200 section 3.3.2.3, Table 3-Ia).
#include <array>
#include <cstdint>

namespace deepnav {

/// One code period as logic bits (0/1), chip 0 first.
using CaCodeBits = std::array<std::uint8_t, 1023>;
/// One code period as signal levels: logic 0 -> +1, logic 1 -> -1.
using CaCodeChips = std::array<std::int8_t, 1023>;

/// Logic bits of the C/A code of a PRN in 1..32; throws std::invalid_argument otherwise.
CaCodeBits ca_code_bits(int prn);
/// Signal levels (+1/-1) of the C/A code; cached, so cheap to call repeatedly.
const CaCodeChips& ca_code_chips(int prn);

}  // namespace deepnav
