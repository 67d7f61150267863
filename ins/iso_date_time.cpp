#include "ins/iso_date_time.hpp"

#include <regex>

namespace deepnav {

std::optional<IsoDateTime> parse_iso_date_time(const std::string& text, bool z_allowed) {
  static const std::regex kIso(R"((\d{4})-(\d{2})-(\d{2})[T ](\d{2}):(\d{2}):(\d{2}(\.\d+)?)(Z?))");
  std::smatch m;
  if (!std::regex_match(text, m, kIso)) return std::nullopt;
  IsoDateTime out;
  out.utc = m[8].length() > 0;
  if (out.utc && !z_allowed) return std::nullopt;
  out.calendar.year = std::stoi(m[1]);
  out.calendar.month = std::stoi(m[2]);
  out.calendar.day = std::stoi(m[3]);
  out.calendar.hour = std::stoi(m[4]);
  out.calendar.minute = std::stoi(m[5]);
  out.calendar.second = std::stod(m[6]);
  return out;
}

}  // namespace deepnav
