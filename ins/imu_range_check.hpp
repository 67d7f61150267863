#pragma once
// Samples an IMU of a given grade cannot have produced: a rate or specific force beyond
// the grade's measurement range (imu_grades.yaml range_deg_per_s, range_g) on any axis.
// The file reader already refuses what no sensor can measure; this is the narrower test
// against the IMU the user says it is (a wrong grade, a spike, a unit error in a column).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "ins/imu_model.hpp"
#include "ins/imu_sample.hpp"

namespace deepnav {

struct ImuRangeExcess {
  std::size_t samples = 0;          ///< samples with an axis beyond the range
  std::optional<double> first_t_s;  ///< the first of them
  std::string first_what;           ///< what it exceeded, for the message
};

/// Checks increments against the grade's ranges (an absent range is not checked).
ImuRangeExcess samples_beyond_range(const std::vector<ImuSample>& samples, const ImuErrorModel& grade);

}  // namespace deepnav
