#include "receiver/pvt/coarse_time_checks.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "ins/wgs84.hpp"

namespace deepnav {

std::string implausible_place(const CheckedCoarseTimeFit& fit, const CoarseTimeConfig& config) {
  const double height_m = wgs84::ecef_to_llh(fit.fit.state.r_ecef_m).height_m;
  if (!(height_m >= config.min_height_m && height_m <= config.max_height_m))
    return fmt::format("implausible height {:.0f} m (accepted {:.0f} to {:.0f} m)", height_m, config.min_height_m,
                       config.max_height_m);
  for (std::size_t k = 0; k < fit.used.size(); ++k) {
    if (fit.fit.elevation_rad[k] < config.min_elevation_rad)
      return fmt::format("PRN {} would be {:.1f} deg below the horizon there", fit.used[k].prn,
                         -fit.fit.elevation_rad[k] * 180.0 / std::numbers::pi);
  }
  return {};
}

std::string time_beyond_tolerance(const CheckedCoarseTimeFit& fit, const CoarseTimeConfig& config) {
  const double correction_s = fit.fit.state.time_correction_s;
  if (std::abs(correction_s) <= config.time_hint_tolerance_s) return {};
  return fmt::format("a time correction of {:+.1f} s, beyond the +-{:.0f} s the method tolerates", correction_s,
                     config.time_hint_tolerance_s);
}

std::string implausibility(const CheckedCoarseTimeFit& fit, const CoarseTimeConfig& config) {
  std::string why = implausible_place(fit, config);
  return why.empty() ? time_beyond_tolerance(fit, config) : why;
}

}  // namespace deepnav
