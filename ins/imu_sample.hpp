#pragma once
// What an IMU delivers, as the mechanization, the filters and the log readers take it
// (the simulator in ins/sim/ makes them too).
#include <Eigen/Core>

namespace deepnav {

/// IMU output: increments over the interval (t_s - 1/rate, t_s].
struct ImuSample {
  double t_s = 0.0;
  Eigen::Vector3d dtheta_b_rad = Eigen::Vector3d::Zero();
  Eigen::Vector3d dv_b_mps = Eigen::Vector3d::Zero();
};

/// Instantaneous IMU rates at t_s.
struct ImuRates {
  double t_s = 0.0;
  Eigen::Vector3d w_ib_b_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d f_b_mps2 = Eigen::Vector3d::Zero();
};

}  // namespace deepnav
