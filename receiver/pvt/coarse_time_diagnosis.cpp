#include "receiver/pvt/coarse_time_diagnosis.hpp"

#include <algorithm>
#include <cmath>

#include "ins/wgs84.hpp"
#include "receiver/pvt/coarse_time_checks.hpp"

namespace deepnav {
namespace {

/// Whether every satellite is above the configured elevation from `position` at `t`
/// (geodetic up; the flight time and Earth rotation change nothing at this scale).
bool all_visible(const std::vector<CoarseTimeSatellite>& satellites, const GpsTime& t,
                 const Eigen::Vector3d& position_ecef_m, double min_elevation_rad) {
  const wgs84::Llh llh = wgs84::ecef_to_llh(position_ecef_m);
  const Eigen::Vector3d up(std::cos(llh.lat_rad) * std::cos(llh.lon_rad), std::cos(llh.lat_rad) * std::sin(llh.lon_rad),
                           std::sin(llh.lat_rad));
  const double min_sin = std::sin(min_elevation_rad);
  return std::all_of(satellites.begin(), satellites.end(), [&](const CoarseTimeSatellite& sat) {
    const Eigen::Vector3d d = satellite_state(*sat.ephemeris, t).r_ecef_m - position_ecef_m;
    return up.dot(d) >= min_sin * d.norm();
  });
}

}  // namespace

TimeScan fit_at_other_times(const std::vector<CoarseTimeSatellite>& satellites, const CoarseTimeContext& context,
                            const Eigen::Vector3d& position_ecef_m, const CoarseTimeConfig& config) {
  TimeScan scan;
  CoarseTimeIntegrityConfig no_exclusions = config.integrity;
  no_exclusions.max_exclusions = 0;
  const double step_s = config.time_hint_tolerance_s;
  const int steps = static_cast<int>(std::floor(config.time_scan_s / step_s));
  for (int i = 1; i <= steps; ++i) {
    for (const double dt : {i * step_s, -i * step_s}) {
      if (!all_visible(satellites, context.t_hint.plus_seconds(dt), position_ecef_m, config.min_elevation_rad))
        continue;
      CoarseTimeState start;
      start.r_ecef_m = position_ecef_m;
      start.time_correction_s = dt;
      const WholeMilliseconds ms = resolve_whole_milliseconds(satellites, context, start);
      CheckedCoarseTimeFit fit = checked_coarse_time_fit(satellites, ms, context, start, no_exclusions);
      ++scan.steps_fitted;
      const double moved_m = (fit.fit.state.r_ecef_m - position_ecef_m).norm();
      if (fit.passed && implausible_place(fit, config).empty() && moved_m <= config.position_hint_tolerance_m) {
        scan.fix = std::move(fit);
        return scan;
      }
    }
  }
  return scan;
}

}  // namespace deepnav
