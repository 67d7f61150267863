#pragma once
// Whether an IMU is at rest, from its samples alone (the recording-driven navigator's
// zero-velocity updates, recorded_fusion.hpp): over the last window the specific force and
// the angular rate each stay within a tolerance of their means (a bias does not matter),
// the mean specific force is gravity's magnitude and the mean angular rate is no more than
// the tolerance plus what the gyro's bias can be.
//
// The variation alone is not enough: a vehicle in a steady turn or at constant speed with
// a quiet IMU passes it (the land circle with a tactical IMU did at every epoch); the rate
// bound catches the turn, the caller's GNSS speed (StationarityConfig::max_gnss_speed_mps)
// the rest.
#include <Eigen/Core>
#include <cmath>
#include <deque>

#include "ins/imu_sample.hpp"

namespace deepnav::aiding {

struct StationarityConfig {
  bool enabled = true;
  double window_s = 0.5;
  double accel_tolerance_mps2 = 0.25;  ///< |f - mean f| within this over the window
  double gyro_tolerance_radps = 0.25 * M_PI / 180.0;
  double velocity_sigma_mps = 0.02;  ///< of the zero-velocity update
  /// No update while the PVT's Doppler velocity is faster than this (m/s).
  double max_gnss_speed_mps = 0.5;
};

class StationarityDetector {
 public:
  /// `gravity_mps2`: its magnitude at the site; `gyro_bias_radps`: the most the gyro's bias
  /// can be (a mean rate within that and the tolerance is rest).
  StationarityDetector(const StationarityConfig& config, double gravity_mps2, double gyro_bias_radps);
  /// A sample and its interval (s; none taken when not positive).
  void add(const ImuSample& sample, double dt_s);
  /// The last window (at least 80 % of window_s, five samples) was at rest.
  bool stationary() const;

 private:
  struct Entry {
    double t_s;
    Eigen::Vector3d f_b_mps2, w_b_radps;
  };
  StationarityConfig cfg_;
  double gravity_mps2_, gyro_bias_radps_;
  std::deque<Entry> window_;
};

}  // namespace deepnav::aiding
