#pragma once
// The I/NAV nominal page on E1-B (Galileo OS SIS ICD 4.3.2): a 128-bit word in two page parts
// of one second each, even then odd, every part 10 synchronisation symbols (0101100000) and
// the 240 FEC symbols of its 120 bits (signals/galileo/inav_fec.hpp): 250 symbols at 250/s.
//
//   even part: even/odd = 0 | page type | word bits 1-112                                | tail
//   odd part:  even/odd = 1 | page type | word bits 113-128 | reserved 1 (40) | SAR (22) |
//              spare (2) | CRC (24) | reserved 2 (8) | tail
//
// The CRC-24Q covers the even part's first 114 bits and the odd part's first 82 (196 bits).
// Reserved 1 carries OSNMA and reserved 2 the secondary synchronisation pattern today; they
// pass through here as bits.
#include <array>
#include <cstdint>

#include "signals/galileo/inav_fec.hpp"
#include "signals/galileo/inav_words.hpp"

namespace deepnav::galileo::inav {

inline constexpr int kSyncSymbols = 10;
inline constexpr std::array<std::uint8_t, kSyncSymbols> kSyncPattern = {0, 1, 0, 1, 1, 0, 0, 0, 0, 0};
inline constexpr int kPagePartTotalSymbols = kSyncSymbols + kPagePartSymbols;  ///< 250: one second
inline constexpr int kCrcBits = 196;

/// The odd part's fields besides the word's last 16 bits.
struct OddPartFields {
  std::uint64_t reserved1 = 0;  ///< 40 bits (OSNMA on E1-B)
  std::uint32_t sar = 0;        ///< 22 bits, search and rescue return link
  std::uint32_t spare = 0;      ///< 2 bits
  std::uint32_t reserved2 = 0;  ///< 8 bits (secondary synchronisation pattern on E1-B)
};

struct NominalPage {
  Word word{};
  bool alert = false;  ///< page type: 0 nominal, 1 alert
  OddPartFields odd;
};

/// The 114 bits (tail excluded) of each page part, CRC included. Throws std::invalid_argument
/// when an odd-part field has more bits than its width.
std::array<PagePartBits, 2> page_part_bits(const NominalPage& page);

/// One page part as transmitted: the sync pattern, then the part's FEC symbols (logic values).
using PagePartTransmission = std::array<std::uint8_t, kPagePartTotalSymbols>;
/// Even and odd part of a page, in transmission order.
std::array<PagePartTransmission, 2> encode_page(const NominalPage& page);

struct DecodedPage {
  NominalPage page;
  bool parts_in_order = false;  ///< the even/odd bits read 0 then 1
  bool crc_ok = false;          ///< the CRC-24Q matched: only then is the word to be trusted
};

/// Decodes a page from the 240 soft symbols that follow the sync pattern in each of its two
/// parts (signal levels, logic 0 positive).
DecodedPage decode_page(const PagePartSoftSymbols& even_part, const PagePartSoftSymbols& odd_part);

}  // namespace deepnav::galileo::inav
