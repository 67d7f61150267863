#include "signals/sim/antenna_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace deepnav {

double antenna_gain_db(const AntennaSpec& spec, double elevation_rad) {
  if (spec.pattern == AntennaSpec::Pattern::isotropic) return 0.0;
  const double x = 1.0 - std::sin(std::clamp(elevation_rad, 0.0, std::numbers::pi / 2.0));
  const double exponent =
      std::log(spec.gain_10deg_db / spec.gain_horizon_db) / std::log(1.0 - std::sin(10.0 * std::numbers::pi / 180.0));
  return spec.gain_horizon_db * std::pow(x, exponent);
}

}  // namespace deepnav
