#include "signals/galileo/crc24q.hpp"

#include <boost/crc.hpp>

namespace deepnav::galileo {

std::uint32_t crc24q(std::span<const std::uint8_t> bits) {
  // Bit by bit: an I/NAV page's CRC covers 196 bits, not whole bytes.
  boost::crc_basic<24> crc(0x864CFB, 0, 0, false, false);
  for (std::uint8_t bit : bits) crc.process_bit(bit != 0);
  return static_cast<std::uint32_t>(crc.checksum());
}

}  // namespace deepnav::galileo
