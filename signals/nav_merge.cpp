#include "signals/nav_merge.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace deepnav {

void shift_galileo_weeks(NavData& nav, int weeks) {
  const auto moved = [weeks](int week, const char* what) {
    if (week + weeks < 0) {
      throw std::invalid_argument(fmt::format(
          "moving the Galileo data by {} weeks puts the {} (GST week {}) before GST week 0", weeks, what, week));
    }
    return week + weeks;
  };
  for (galileo::GalileoEphemeris& eph : nav.galileo_ephemerides)
    eph.week = moved(eph.week, fmt::format("record of E{:02d}", eph.prn).c_str());
  if (nav.ggto.valid) nav.ggto.wn0g = moved(nav.ggto.wn0g, "GGTO reference week (GAGP)");
  if (nav.galileo_utc.valid) nav.galileo_utc.wnt = moved(nav.galileo_utc.wnt, "GST-UTC reference week (GAUT)");
}

bool from_e1b_inav(const galileo::GalileoEphemeris& eph) { return (eph.data_sources & 1) != 0; }

NavData merge_gps_galileo(const NavData& gps, const NavData& galileo, const NavMergeRequest& request) {
  if (gps.ephemerides.empty())
    throw std::runtime_error(fmt::format("{}: no GPS record (the GPS navigation file was expected)", gps.source));
  NavData out;
  out.ephemerides = gps.ephemerides;
  out.iono = gps.iono;
  out.utc = gps.utc;
  out.leap_seconds_valid = gps.leap_seconds_valid;
  for (const galileo::GalileoEphemeris& eph : galileo.galileo_ephemerides) {
    if (!request.inav_only || from_e1b_inav(eph)) out.galileo_ephemerides.push_back(eph);
  }
  if (out.galileo_ephemerides.empty()) {
    throw std::runtime_error(fmt::format("{}: no Galileo record{} (the Galileo navigation file was expected)",
                                         galileo.source, request.inav_only ? " from E1-B I/NAV" : ""));
  }
  out.galileo_iono = galileo.galileo_iono;
  out.ggto = galileo.ggto;
  out.galileo_utc = galileo.galileo_utc;
  out.rinex_version = 3.04;
  out.source = fmt::format("{} + {}", gps.source, galileo.source);
  shift_galileo_weeks(out, request.galileo_week_shift);
  return out;
}

}  // namespace deepnav
