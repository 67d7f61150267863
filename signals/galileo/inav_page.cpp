#include "signals/galileo/inav_page.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <vector>

#include "signals/galileo/crc24q.hpp"

namespace deepnav::galileo::inav {
namespace {

constexpr int kEvenWordBits = 112;
constexpr int kCrcStartInOddPart = 82;
constexpr int kEvenCrcBits = 114;

/// Sequential access to a part's bits.
class BitCursor {
 public:
  explicit BitCursor(PagePartBits& bits) : bits_(bits) {}

  void put(std::uint64_t value, int width, const char* name) {
    if (width < 64 && (value >> width) != 0) {
      throw std::invalid_argument(fmt::format("I/NAV page: {} = {} has more than {} bits", name, value, width));
    }
    for (int k = width - 1; k >= 0; --k) bits_[static_cast<std::size_t>(pos_++)] = k < 64 && ((value >> k) & 1);
  }
  std::uint64_t get(int width) {
    std::uint64_t value = 0;
    for (int k = 0; k < width; ++k) value = (value << 1) | bits_[static_cast<std::size_t>(pos_++)];
    return value;
  }

 private:
  PagePartBits& bits_;
  int pos_ = 0;
};

std::uint32_t page_crc(const PagePartBits& even, const PagePartBits& odd) {
  std::vector<std::uint8_t> covered(even.begin(), even.begin() + kEvenCrcBits);
  covered.insert(covered.end(), odd.begin(), odd.begin() + kCrcStartInOddPart);
  return crc24q(covered);
}

PagePartTransmission transmission(const PagePartBits& bits) {
  PagePartTransmission out{};
  std::copy(kSyncPattern.begin(), kSyncPattern.end(), out.begin());
  const PagePartSymbols symbols = encode_page_part(bits);
  std::copy(symbols.begin(), symbols.end(), out.begin() + kSyncSymbols);
  return out;
}

}  // namespace

std::array<PagePartBits, 2> page_part_bits(const NominalPage& page) {
  PagePartBits even{}, odd{};
  BitCursor e(even);
  e.put(0, 1, "even/odd");
  e.put(page.alert, 1, "page type");
  for (int i = 0; i < kEvenWordBits; ++i) e.put(page.word[static_cast<std::size_t>(i)], 1, "word bit");
  BitCursor o(odd);
  o.put(1, 1, "even/odd");
  o.put(page.alert, 1, "page type");
  for (int i = kEvenWordBits; i < kWordBits; ++i) o.put(page.word[static_cast<std::size_t>(i)], 1, "word bit");
  o.put(page.odd.reserved1, 40, "reserved 1");
  o.put(page.odd.sar, 22, "SAR");
  o.put(page.odd.spare, 2, "spare");
  o.put(page_crc(even, odd), 24, "CRC");  // the bits it covers are all written by now
  o.put(page.odd.reserved2, 8, "reserved 2");
  return {even, odd};
}

std::array<PagePartTransmission, 2> encode_page(const NominalPage& page) {
  const std::array<PagePartBits, 2> parts = page_part_bits(page);
  return {transmission(parts[0]), transmission(parts[1])};
}

DecodedPage decode_page(const PagePartSoftSymbols& even_part, const PagePartSoftSymbols& odd_part) {
  PagePartBits even = decode_page_part(even_part);
  PagePartBits odd = decode_page_part(odd_part);
  DecodedPage out;
  BitCursor e(even), o(odd);
  const bool even_flag = e.get(1) != 0;
  const bool alert_even = e.get(1) != 0;
  for (int i = 0; i < kEvenWordBits; ++i)
    out.page.word[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(e.get(1));
  const bool odd_flag = o.get(1) != 0;
  const bool alert_odd = o.get(1) != 0;
  for (int i = kEvenWordBits; i < kWordBits; ++i)
    out.page.word[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(o.get(1));
  out.page.odd.reserved1 = o.get(40);
  out.page.odd.sar = static_cast<std::uint32_t>(o.get(22));
  out.page.odd.spare = static_cast<std::uint32_t>(o.get(2));
  const auto crc = static_cast<std::uint32_t>(o.get(24));
  out.page.odd.reserved2 = static_cast<std::uint32_t>(o.get(8));
  out.page.alert = alert_even || alert_odd;
  out.parts_in_order = !even_flag && odd_flag;
  out.crc_ok = crc == page_crc(even, odd);
  return out;
}

}  // namespace deepnav::galileo::inav
