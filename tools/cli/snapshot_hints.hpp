#pragma once
// The coarse-time hints as the command line writes them (`deepnav snap`, and `deepnav run`'s
// hot start): --time-hint (a date and time, UTC with a trailing Z, else GPS time) and
// --position-hint LAT,LON,H (degrees, degrees, metres above the WGS-84 ellipsoid). Without
// --time-hint, the date an ION metadata file gives the recording serves as the time hint.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "ins/gps_time.hpp"
#include "receiver/sources/source_settings.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::cli {

/// UTC - GPS offset (s) a UTC time hint is converted with: the navigation file's LEAP
/// SECONDS, else 18 (since 2017).
int leap_seconds_of(const NavData& nav);

/// "2022-01-01T00:00:03Z" (UTC: GPS time is ahead by `leap_seconds`) or
/// "2022-01-01T00:00:21" (GPS time); a space may replace the T and seconds may have a
/// fraction. Throws UserError naming --time-hint and the expected form.
GpsTime parse_time_hint(const std::string& text, int leap_seconds);

/// The time of the file's first sample: --time-hint when given, else the metadata file's
/// date of the recording (UTC, its <file><timestamp> or <session><toa>), logged with where
/// it came from; nullopt with neither.
std::optional<GpsTime> first_sample_time_hint(const std::string& time_hint, const SourceSettings& source,
                                              int leap_seconds);

/// "LAT,LON,H" to ECEF (m). Throws UserError naming --position-hint for a malformed text,
/// a latitude outside [-90, 90], a longitude outside [-180, 360] or a height outside
/// [-1000, 100000] m.
Eigen::Vector3d parse_position_hint(const std::string& text);

}  // namespace deepnav::cli
