#pragma once
// Readings of an IMU at rest on the Earth (the input of the alignment algorithms):
// f_b = C_n^b [0 0 -g] + b_a + noise, w_b = C_n^b w_ie_n + b_g + noise, with constant
// biases given in body axes and white noise from the seeded generator.
#include <Eigen/Core>
#include <random>
#include <vector>

#include "ins/lever_arm_imu_sim.hpp"

namespace deepnav {

struct StaticImuErrors {
  Eigen::Vector3d accel_bias_b_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_b_radps = Eigen::Vector3d::Zero();
  double accel_noise_density_mps2_per_rthz = 0.0;  ///< VRW
  double gyro_noise_density_radps_per_rthz = 0.0;  ///< ARW
};

/// Readings at t = k / rate for k = 0 .. round(duration * rate) - 1. Throws
/// std::invalid_argument for a non-positive duration or rate.
std::vector<ImuReading> simulate_static_imu(const Eigen::Matrix3d& C_b_n, double lat_rad, double gravity_mps2,
                                            const StaticImuErrors& errors, double duration_s, double rate_hz,
                                            std::mt19937_64& rng);

}  // namespace deepnav
