#include "tools/cli/snapshot_hints.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <sstream>
#include <vector>

#include "ins/iso_date_time.hpp"
#include "ins/wgs84.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double number_in(const std::string& item, double lo, double hi, const std::string& what, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(item, &used);
    if (used == item.size() && v >= lo && v <= hi) return v;
  } catch (const std::exception&) {
  }
  throw UserError(
      fmt::format("--position-hint '{}': {} '{}' is not a number in [{}, {}] (expected LAT,LON,H in "
                  "degrees, degrees and metres, e.g. 37.5,127.0,50)",
                  text, what, item, lo, hi));
}

}  // namespace

int leap_seconds_of(const NavData& nav) {
  constexpr int kLeapSecondsSince2017 = 18;
  return nav.leap_seconds_valid ? nav.utc.delta_t_ls : kLeapSecondsSince2017;
}

GpsTime parse_time_hint(const std::string& text, int leap_seconds) {
  const std::string expected = "expected a date and time like 2022-01-01T00:00:03Z (UTC) or 2022-01-01T00:00:21 (GPS)";
  const std::optional<IsoDateTime> written = parse_iso_date_time(text, true);
  if (!written) throw UserError(fmt::format("--time-hint '{}': {}", text, expected));
  if (!is_valid_calendar(written->calendar) || written->calendar.year < 1980)
    throw UserError(
        fmt::format("--time-hint '{}' is not a real date and time after the GPS epoch ({})", text, expected));
  const GpsTime t = gps_time_from_calendar(written->calendar);
  return written->utc ? t.plus_seconds(leap_seconds) : t;
}

std::optional<GpsTime> first_sample_time_hint(const std::string& time_hint, const SourceSettings& source,
                                              int leap_seconds) {
  if (!time_hint.empty()) return parse_time_hint(time_hint, leap_seconds);
  if (!source.start_time_utc) return std::nullopt;
  const CalendarTime& c = *source.start_time_utc;
  spdlog::info("time hint: {:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:06.3f}Z from {}", c.year, c.month, c.day, c.hour,
               c.minute, c.second, source.start_time_origin);
  return gps_time_from_calendar(c).plus_seconds(leap_seconds);
}

Eigen::Vector3d parse_position_hint(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');) items.push_back(item);
  if (items.size() != 3)
    throw UserError(fmt::format("--position-hint '{}': expected LAT,LON,H (three numbers, e.g. 37.5,127.0,50)", text));
  const double lat = number_in(items[0], -90.0, 90.0, "latitude", text);
  const double lon = number_in(items[1], -180.0, 360.0, "longitude", text);
  const double h = number_in(items[2], -1000.0, 100000.0, "height", text);
  return wgs84::llh_to_ecef({lat * kDeg, lon * kDeg, h});
}

}  // namespace deepnav::cli
