#include "signals/galileo/e1_codes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "signals/galileo/e1_code_tables.hpp"

namespace deepnav::galileo {
namespace {

/// Value of one hexadecimal digit, or -1.
int hex_digit_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

using CodeTable = std::array<E1CodeChips, detail::kE1PrimaryCodeCount>;

CodeTable decode_table(const std::array<std::string_view, detail::kE1PrimaryCodeCount>& hex, const char* name) {
  CodeTable table{};
  for (std::size_t i = 0; i < hex.size(); ++i) {
    const std::vector<std::int8_t> chips =
        chips_from_hex(hex[i], kE1CodeLength_chips, fmt::format("{} primary code of PRN {}", name, i + 1));
    std::copy(chips.begin(), chips.end(), table[i].begin());
  }
  return table;
}

void check_prn(int prn, const char* name) {
  if (prn < 1 || prn > kMaxPrn) {
    throw std::invalid_argument(fmt::format("{} primary code: PRN {} is not in 1..{}", name, prn, kMaxPrn));
  }
}

}  // namespace

std::vector<std::int8_t> chips_from_hex(std::string_view hex, int chips, std::string_view what) {
  const std::size_t digits = static_cast<std::size_t>((chips + 3) / 4);
  if (chips <= 0 || hex.size() != digits) {
    throw std::invalid_argument(
        fmt::format("{}: expected {} hexadecimal digits for {} chips, got {}", what, digits, chips, hex.size()));
  }
  std::vector<std::int8_t> out;
  out.reserve(static_cast<std::size_t>(chips));
  for (std::size_t d = 0; d < digits; ++d) {
    const int value = hex_digit_value(hex[d]);
    if (value < 0) throw std::invalid_argument(fmt::format("{}: '{}' at digit {} is not hexadecimal", what, hex[d], d));
    for (int bit = 3; bit >= 0; --bit) {
      const bool one = (value >> bit) & 1;
      if (static_cast<int>(out.size()) < chips) {
        out.push_back(one ? std::int8_t{-1} : std::int8_t{1});
      } else if (one) {
        throw std::invalid_argument(fmt::format("{}: the last digit's padding bits must be zero", what));
      }
    }
  }
  return out;
}

const E1CodeChips& e1b_code_chips(int prn) {
  check_prn(prn, "E1-B");
  static const CodeTable table = decode_table(detail::kE1bPrimaryHex, "E1-B");
  return table[static_cast<std::size_t>(prn - 1)];
}

const E1CodeChips& e1c_code_chips(int prn) {
  check_prn(prn, "E1-C");
  static const CodeTable table = decode_table(detail::kE1cPrimaryHex, "E1-C");
  return table[static_cast<std::size_t>(prn - 1)];
}

const E1SecondaryChips& e1c_secondary_chips() {
  static const E1SecondaryChips chips = [] {
    const std::vector<std::int8_t> v = chips_from_hex("380AD90", kE1cSecondaryLength_chips, "CS25");
    E1SecondaryChips out{};
    std::copy(v.begin(), v.end(), out.begin());
    return out;
  }();
  return chips;
}

}  // namespace deepnav::galileo
