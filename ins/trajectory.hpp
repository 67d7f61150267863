#pragma once
// A vehicle trajectory: the full kinematic state at any time, analytically or by
// smooth interpolation. Every generator in the project (IF synthesizer, IMU
// simulator, scoring against truth) samples one of these.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>

namespace deepnav {

/// Kinematic state of the body (vehicle) frame at time t (seconds from the start).
/// Attitude and rates follow the papers' convention [docs/references.md]: body axes x forward, y right,
/// z down; NED navigation frame; C_b_n rotates body vectors into NED.
struct TrajectoryState {
  double t_s = 0.0;
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_ecef_mps2 = Eigen::Vector3d::Zero();  ///< d(v_ecef)/dt, kinematic (not specific force)
  Eigen::Vector3d v_ned_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_ned_mps2 = Eigen::Vector3d::Zero();       ///< d(v_ned)/dt as seen in the local NED frame
  Eigen::Quaterniond q_b_n = Eigen::Quaterniond::Identity();  ///< body -> NED
  Eigen::Vector3d w_nb_b_radps = Eigen::Vector3d::Zero();     ///< body rate w.r.t. NED, in body axes
  Eigen::Vector3d dw_nb_b_radps2 = Eigen::Vector3d::Zero();   ///< its time derivative
};

class Trajectory {
 public:
  virtual ~Trajectory() = default;
  virtual TrajectoryState at(double t_s) const = 0;
  /// Length of time the trajectory is defined for (infinity for open-ended ones).
  virtual double duration_s() const = 0;
  virtual std::string description() const = 0;
};

}  // namespace deepnav
