#pragma once
// Strapdown inertial navigation in the local-level NED frame.
//
// Why NED: the aiding filter's error states, the papers' equations [docs/references.md] and every report
// are NED; latitude/longitude/height kept directly as the position avoid an
// ECEF -> geodetic conversion per step. (The frame is singular only at the poles.)
//
// One update per IMU sample (increments over the interval ending at t_k), after
// Savage's two-speed algorithm collapsed to the IMU rate:
//   attitude: body rotation vector with the two-sample (previous-sample) coning term
//             phi = dtheta_k + 1/12 dtheta_{k-1} x dtheta_k, and the navigation-frame
//             rotation zeta = (w_ie_n + w_en_n) dt; q_b_n <- q(-zeta) q_b_n q(phi)
//   velocity: dv_b = dv_k + 1/2 dtheta_k x dv_k + 1/6 dtheta_k x (dtheta_k x dv_k)
//                        (rotation compensation; the third-order term removes a
//                        gravity rectification of g |dtheta|^2 / 6 under vibration)
//                        + 1/12 (dtheta_{k-1} x dv_k + dv_{k-1} x dtheta_k) (sculling),
//             v_n += (I - 1/2 [zeta x]) C_b_n dv_b + (g_n - (2 w_ie_n + w_en_n) x v_n) dt
//             with Earth/transport rate, gravity and the Coriolis velocity evaluated at
//             the middle of the interval (extrapolated from the previous step);
//   position: height, then latitude, then longitude by the trapezoidal rule on the
//             velocity with the radii of curvature at the interval's middle.
// Gravity is wgs84::normal_gravity_mps2 along the NED down axis.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ins/imu_sample.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {

struct NavState {
  double t_s = 0.0;  ///< time of validity, seconds on the IMU's clock
  wgs84::Llh llh;
  Eigen::Vector3d v_ned_mps = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_b_n = Eigen::Quaterniond::Identity();  ///< body -> NED
};

class StrapdownNed {
 public:
  explicit StrapdownNed(const NavState& initial);

  /// Advances the state to sample.t_s with the increments over (state.t_s, sample.t_s].
  /// Throws std::invalid_argument (naming the times) if sample.t_s is not after the
  /// state's time or an increment is not finite. An interval longer than 1.5x the
  /// previous one (a gap in the data) drops the coning/sculling history instead of
  /// pairing samples that are not adjacent.
  void update(const ImuSample& sample);

  const NavState& state() const { return state_; }
  /// Replaces the state (re-initialisation) and forgets the coning/sculling history.
  void reset(const NavState& state);

  // Feedback from the aiding filter. Each adds the correction it is given: a filter
  // that estimates an error (estimate minus truth) passes minus that error.
  /// Moves the position by dr_ned_m (north, east, down metres).
  void correct_position(const Eigen::Vector3d& dr_ned_m);
  void correct_velocity(const Eigen::Vector3d& dv_ned_mps);
  /// Rotates the attitude by the small NED rotation dpsi: C_b_n <- exp([dpsi x]) C_b_n.
  /// (With tilt error eps defined by C_est = (I + [eps x]) C_true, pass -eps.)
  void correct_attitude(const Eigen::Vector3d& dpsi_ned_rad);
  /// Biases removed from every following raw sample (as b * dt) before the update.
  void set_bias_compensation(const Eigen::Vector3d& accel_bias_mps2, const Eigen::Vector3d& gyro_bias_radps);
  const Eigen::Vector3d& accel_bias_compensation_mps2() const { return accel_bias_mps2_; }
  const Eigen::Vector3d& gyro_bias_compensation_radps() const { return gyro_bias_radps_; }

 private:
  NavState state_;
  Eigen::Vector3d accel_bias_mps2_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_radps_ = Eigen::Vector3d::Zero();
  // Previous (bias-compensated) increments, for the coning and sculling terms.
  bool have_previous_ = false;
  double previous_dt_s_ = 0.0;
  Eigen::Vector3d previous_dtheta_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d previous_dv_ = Eigen::Vector3d::Zero();
  // Changes over the previous step, to extrapolate to the middle of the next interval.
  Eigen::Vector3d previous_dv_ned_ = Eigen::Vector3d::Zero();
  double previous_dlat_ = 0.0;
  double previous_dh_ = 0.0;
};

}  // namespace deepnav
