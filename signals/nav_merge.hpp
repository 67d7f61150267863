#pragma once
// Building one mixed GPS + Galileo navigation data set from two broadcast files that cover
// different days: the Galileo data are moved by whole GPS weeks onto the GPS file's week.
// The broadcast model gives ECEF positions as a function of time since toe, and toe moves with
// the records: a whole-week move keeps every satellite at the same ECEF position at the same
// second of week, so the moved constellation has the real one's geometry of that weekday and
// time of day, on the new date. (It is not the sky of the new date, which no file records.)
#include "signals/rinex_nav.hpp"

namespace deepnav {

/// Adds `weeks` to every week number of the Galileo data: each record's toe/toc week (the
/// transmission time is counted from it), the GGTO reference week (GAGP) and the GST-UTC
/// reference week (GAUT). Seconds of week are unchanged. Throws std::invalid_argument when a
/// week would become negative.
void shift_galileo_weeks(NavData& nav, int weeks);

/// Whether a Galileo record was decoded from I/NAV on E1-B (RINEX data sources bit 0).
bool from_e1b_inav(const galileo::GalileoEphemeris& eph);

struct NavMergeRequest {
  int galileo_week_shift = 0;  ///< weeks added to the Galileo data (shift_galileo_weeks)
  bool inav_only = true;       ///< keep only Galileo records from E1-B I/NAV
};

/// GPS records and parameters (Klobuchar, GPS-UTC, leap seconds) of `gps`, Galileo records
/// and parameters (NeQuick G, GGTO, GST-UTC) of `galileo`, moved by the request's weeks.
/// Throws std::runtime_error naming the file (NavData::source) when `gps` holds no GPS record
/// or `galileo` no Galileo record (after the I/NAV filter).
NavData merge_gps_galileo(const NavData& gps, const NavData& galileo, const NavMergeRequest& request);

}  // namespace deepnav
