#pragma once
// IMU readings of a sensor mounted at a lever arm from the rotation centre (the
// centre of gravity, which does not translate): paper 004 [docs/references.md] eq. 14,
//   f_b = -C_n^b g_n + ([w x][w x] + [w' x]) L_b + accelerometer errors,
//   w_meas = w_nb_b + gyro drift (first-order Markov) + white noise.
// Earth rate is left out: an industrial MEMS gyro cannot see it in these scenarios.
#include <Eigen/Core>
#include <random>
#include <vector>

#include "ins/ship_roll_model.hpp"

namespace deepnav {

/// Error figures of a MEMS IMU (1-sigma, SI units).
struct MemsImuFigures {
  double gyro_noise_density_radps_per_rthz = 0.0;  ///< angle random walk
  double gyro_drift_sigma_radps = 0.0;             ///< first-order Markov drift, steady-state sigma
  double gyro_drift_tau_s = 1.0;                   ///< its correlation time (beta = 1/tau)
  double accel_noise_density_mps2_per_rthz = 0.0;  ///< velocity random walk
  double accel_bias_sigma_mps2 = 0.0;              ///< constant per run, drawn once

  /// Industrial-grade MEMS in the class of the paper's LandMark30 (our figures, the paper
  /// gives none): 0.3 deg/sqrt(h) ARW, 72 deg/h Markov drift with 300 s correlation time,
  /// 100 ug/sqrt(Hz) accelerometer noise, 1 mg accelerometer bias.
  static MemsImuFigures industrial();
};

struct ImuReading {
  double t_s = 0.0;
  Eigen::Vector3d f_b_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_ib_b_radps = Eigen::Vector3d::Zero();
};

/// Specific force sensed at lever arm L_b from the rotation centre, without sensor errors.
Eigen::Vector3d specific_force_at_lever_arm(const AttitudeTruth& truth, const Eigen::Vector3d& lever_b_m,
                                            double gravity_mps2);

/// Lever-arm acceleration matrix K = [w x][w x] + [w' x], so that the arm contributes K L_b.
Eigen::Matrix3d lever_arm_matrix(const Eigen::Vector3d& w_b_radps, const Eigen::Vector3d& dw_b_radps2);

/// Readings at every truth sample (uniformly spaced), errors drawn from rng.
std::vector<ImuReading> simulate_lever_arm_imu(const std::vector<AttitudeTruth>& truth,
                                               const Eigen::Vector3d& lever_b_m, const MemsImuFigures& imu,
                                               double gravity_mps2, std::mt19937_64& rng);

}  // namespace deepnav
