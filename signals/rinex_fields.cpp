#include "signals/rinex_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace deepnav::rinex {

std::string_view column(std::string_view line, std::size_t start, std::size_t width) {
  if (start >= line.size()) return {};
  return line.substr(start, std::min(width, line.size() - start));
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(' ');
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(' ');
  return s.substr(first, last - first + 1);
}

std::optional<double> parse_number(std::string_view field) {
  const std::string_view text = trim(field);
  if (text.empty()) return std::nullopt;
  std::string buf(text);
  for (char& ch : buf) {
    if (ch == 'D' || ch == 'd') ch = 'E';
    // Only what a RINEX number can contain.
    const bool allowed = (ch >= '0' && ch <= '9') || ch == '+' || ch == '-' || ch == '.' || ch == 'E' || ch == 'e';
    if (!allowed) throw std::invalid_argument(fmt::format("expected a number, got '{}'", text));
  }
  char* end = nullptr;
  const double value = std::strtod(buf.c_str(), &end);
  if (end != buf.c_str() + buf.size() || !std::isfinite(value))
    throw std::invalid_argument(fmt::format("expected a finite number, got '{}'", text));
  return value;
}

}  // namespace deepnav::rinex
