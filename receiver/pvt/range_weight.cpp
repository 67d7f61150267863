#include "receiver/pvt/range_weight.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav {

double RangeErrorModel::model_variance_m2(double elevation_rad) const {
  const double s = std::max(std::sin(elevation_rad), min_sin_elevation);
  return floor_m * floor_m + elevation_m * elevation_m / (s * s);
}

double RangeErrorModel::model_variance_per_row_m2(double elevation_rad, double row_interval_s) const {
  constexpr double kStatedInterval_s = 1.0;  // the a and b terms hold for one row per second
  return model_variance_m2(elevation_rad) * std::max(1.0, kStatedInterval_s / row_interval_s);
}

double RangeErrorModel::thermal_variance_m2(double cn0_dbhz) const {
  return thermal_m2hz * std::pow(10.0, -cn0_dbhz / 10.0);
}

}  // namespace deepnav
