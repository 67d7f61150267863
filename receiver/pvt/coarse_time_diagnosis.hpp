#pragma once
// When the code phases do not fit the hints: at which time they fit the hinted position.
// A time hint off by more than the method tolerates gives wrong whole milliseconds and
// residuals that say only "something is wrong"; fitted again from the hinted position
// at times stepped through `time_scan_s` each way (step: time_hint_tolerance_s, so every
// time lies within half of it from a step), the right time gives a fix that passes its
// test, and its time correction says by how much the hint is off.
//
// Steps at which a satellite would be below the hinted position's horizon are skipped.
// Fits run without exclusions: with hundreds of tries, dropping a satellite would let a
// wrong time pass.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "receiver/pvt/coarse_time_config.hpp"
#include "receiver/pvt/coarse_time_fit.hpp"
#include "receiver/pvt/coarse_time_integrity.hpp"

namespace deepnav {

struct TimeScan {
  std::optional<CheckedCoarseTimeFit> fix;  ///< the first that passes, nearest the hint; its place is plausible
  int steps_fitted = 0;
};

/// Fits from `position_ecef_m` at t_hint + dt for dt = +-step, +-2 step, ... up to
/// config.time_scan_s, nearest first; keeps the first fix that passes and lies within
/// config.position_hint_tolerance_m of the position.
TimeScan fit_at_other_times(const std::vector<CoarseTimeSatellite>& satellites, const CoarseTimeContext& context,
                            const Eigen::Vector3d& position_ecef_m, const CoarseTimeConfig& config);

}  // namespace deepnav
