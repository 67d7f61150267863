#pragma once
// Stationary fine alignment: an attitude/velocity mechanization at rest, closed by a
// 12-state error Kalman filter with zero-velocity updates (ZUPT).
//
// Error model (phi-angle form, NED, vehicle at rest, Titterton & Weston ch. 12):
//   C_b_n_est = (I - [phi x]) C_b_n_true
//   phi'   = -w_ie_n x phi - db_g_n
//   dv'    =  f_n x phi - 2 w_ie_n x dv + db_a_n,   f_n = [0 0 -g] at rest
//   db_a_n' = 0, db_g_n' = 0
// with db = true bias - estimated bias, resolved in NED: at rest C_b_n is constant, so the
// NED-resolved biases are constant too, and the covariance no longer depends on the
// heading estimate. (With body-frame bias states, every heading correction rotates what
// the filter has learned about the north gyro bias into the unobservable east one and
// the filter becomes overconfident and biased.) The ZUPT measures dv = v_est (truth is zero).
// Corrections are fed back after every update (closed loop), so the states stay small.
// The prediction and the update are the project's Kalman filter (kalman_filter.hpp); a
// variance may be zero here (a bias the configuration says is absent).
//
// At rest the east gyro bias and the heading error are not separable: the heading
// settles at the gyrocompassing limit eps_D = -db_gE / (w_ie cos L), the levels at the
// accelerometer limit (-df_E/g, df_N/g). See gyrocompass_heading_limit_rad.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "ins/kalman_filter.hpp"
#include "ins/lever_arm_imu_sim.hpp"

namespace deepnav {

struct FineAlignmentConfig {
  double lat_rad = 0.0;
  double gravity_mps2 = 9.80665;
  double zupt_interval_s = 0.1;  ///< one zero-velocity update per interval
  double zupt_sigma_mps = 1e-3;  ///< ZUPT measurement noise (a parked vehicle's sway)
  double gyro_noise_density_radps_per_rthz = 0.0;
  double accel_noise_density_mps2_per_rthz = 0.0;
  double gyro_bias_sigma_radps = 0.0;  ///< prior 1 sigma of the gyro bias
  double accel_bias_sigma_mps2 = 0.0;  ///< prior 1 sigma of the accelerometer bias
  double initial_tilt_sigma_rad = 0.02;
  double initial_heading_sigma_rad = 0.3;
};

/// Heading error the stationary alignment converges to for an east gyro error dw_E
/// (rad/s, in NED): eps_D = -dw_E / (w_ie cos L), in the tilt convention of
/// coarse_alignment.hpp. Its magnitude is the "gyro-bias limit".
double gyrocompass_heading_limit_rad(double dw_east_radps, double lat_rad);

class FineAlignment {
 public:
  /// C_b_n0 from a coarse alignment. Throws std::invalid_argument on a non-positive
  /// zupt_interval_s or zupt_sigma_mps.
  FineAlignment(const FineAlignmentConfig& config, const Eigen::Matrix3d& C_b_n0);

  /// One IMU reading (rates, dt since the previous one). Runs a ZUPT whenever a whole
  /// zupt_interval_s has elapsed (counted in samples, not accumulated time).
  void step(const ImuReading& reading, double dt_s);

  const Eigen::Matrix3d& C_b_n() const { return C_b_n_; }
  const Eigen::Vector3d& v_ned_mps() const { return v_ned_mps_; }
  const Eigen::Vector3d& gyro_bias_radps() const { return gyro_bias_radps_; }
  const Eigen::Vector3d& accel_bias_mps2() const { return accel_bias_mps2_; }
  /// 1-sigma of the attitude error (N, E, D), from the filter covariance.
  Eigen::Vector3d attitude_sigma_rad() const;
  /// false once the filter's covariance failed its check (reason in health_reason());
  /// the mechanization then runs on without corrections.
  bool healthy() const { return kf_.healthy(); }
  const std::string& health_reason() const { return kf_.reason(); }

 private:
  using Filter = KalmanFilter<12>;
  void zupt();
  FineAlignmentConfig config_;
  Eigen::Matrix3d C_b_n_;
  Eigen::Vector3d v_ned_mps_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_radps_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_mps2_ = Eigen::Vector3d::Zero();
  Filter kf_;  ///< error states: tilt (3), velocity (3), accelerometer and gyro bias (3 + 3, NED)
  double time_since_zupt_s_ = 0.0;
  long samples_since_zupt_ = 0;
  long samples_per_zupt_ = 0;
  double sample_dt_s_ = 0.0;
};

/// Heading/tilt error history of a fine alignment against a known true attitude.
struct FineAlignmentTrace {
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> tilt_error_rad;      ///< (I + [eps x]) convention, vs truth
  std::vector<Eigen::Vector3d> attitude_sigma_rad;  ///< filter 1 sigma
};

/// Runs the filter over readings, starting from C_b_n0, sampling the error every
/// trace_interval_s against C_b_n_true.
FineAlignmentTrace run_fine_alignment(const std::vector<ImuReading>& imu, const FineAlignmentConfig& config,
                                      const Eigen::Matrix3d& C_b_n0, const Eigen::Matrix3d& C_b_n_true,
                                      double trace_interval_s = 1.0);

/// First time after which |heading error - target| stays within tolerance until the end
/// of the trace (infinity if it never settles).
double heading_settling_time_s(const FineAlignmentTrace& trace, double target_rad, double tolerance_rad);

}  // namespace deepnav
