#pragma once
// Attitude EKF of paper 004 [docs/references.md] with the lever arm as a state.
//
// State x = [q (4, body->NED quaternion, scalar first), mu (3, gyro drift, first-order
// Markov with rate beta and steady-state sigma), L (0, 1 or 3 lever-arm components,
// random walk)]. The paper's filter is LeverArmModel::kVertical (8 states: L = [0 0 l_cg]);
// kNone is the conventional 7-state filter the paper compares against; kFull3d (10 states)
// estimates the whole arm, which only works when the motion makes it observable.
//
// Process (paper eq. 1-8): q' = 1/2 Omega(w_meas - mu) q, mu' = -beta mu + sigma sqrt(2 beta) w,
// L' = w_lever (PSD lambda). Gyro white noise also drives q (the paper leaves it out of Q;
// without it the filter becomes overconfident in the gyros).
// Measurement (eq. 14-16): f_b = -C_n^b [0 0 g] + ([w x][w x] + [w' x]) L + n, with
// w = w_meas - mu and w' supplied by the caller (e.g. smoothed_angular_acceleration).
// The state is propagated here (exact rotation, exact Markov decay); the covariance, the
// update and the health checks are the project's Kalman filter (kalman_filter.hpp). A
// variance may be zero (the quaternion's covariance has rank 3, and a component of a
// unit quaternion can be known exactly).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "ins/kalman_filter.hpp"
#include "ins/lever_arm_imu_sim.hpp"

namespace deepnav {

enum class LeverArmModel { kNone, kVertical, kFull3d };

struct LeverArmEkfConfig {
  LeverArmModel model = LeverArmModel::kVertical;
  double gravity_mps2 = 9.80665;
  double gyro_noise_density_radps_per_rthz = 0.0;  ///< drives the quaternion
  double gyro_drift_sigma_radps = 0.0;             ///< Markov steady-state sigma
  double gyro_drift_tau_s = 300.0;                 ///< Markov correlation time (1/beta)
  double accel_sigma_mps2 = 0.05;                  ///< R = sigma^2 I per update (noise + unmodelled motion)
  double lever_psd_m2ps = 1e-6;                    ///< lambda of eq. 18
  double initial_attitude_sigma_rad = 0.02;
  double initial_drift_sigma_radps = 0.0;  ///< 0: use gyro_drift_sigma_radps
  double initial_lever_sigma_m = 1.0;
  Eigen::Vector3d initial_lever_b_m = Eigen::Vector3d::Zero();
  double observability_sigma_limit_m =
      0.05;  ///< a direction whose information-only sigma exceeds this is "not observable"
};

/// The tuning used for paper 004's scenarios with an IMU of the given figures. The paper
/// gives no R; sigma = 1 m/s^2 stands for the motion terms it neglects (v' + w x v, wave
/// heave) and reproduces the size of its conventional-filter errors. lambda = 1e-6 m^2/s.
LeverArmEkfConfig paper004_config(LeverArmModel model, const MemsImuFigures& imu, double gravity_mps2 = 9.80665);

/// Which lever-arm directions the angular motion has made observable: the information
/// sum_k K_k^T K_k / sigma^2 (K = [w x][w x] + [w' x]) and its eigen-decomposition.
struct LeverArmObservability {
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();     ///< ascending
  Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();  ///< unit eigenvectors (columns, body axes)
  Eigen::Vector3d sigma_m = Eigen::Vector3d::Zero();         ///< 1/sqrt(eigenvalue), infinity if zero
  bool fully_observable = false;
  std::string summary;  ///< human-readable: "observable" or which direction is not, and why
};
LeverArmObservability assess_lever_arm_observability(const Eigen::Matrix3d& information, double sigma_limit_m);

class LeverArmEkf {
 public:
  LeverArmEkf(const LeverArmEkfConfig& config, const Eigen::Quaterniond& q_b_n0);

  /// Time update over dt with the measured body rate.
  void propagate(const Eigen::Vector3d& w_meas_radps, double dt_s);
  /// Accelerometer update; w_meas and dw are the measured rate and angular acceleration at
  /// the same instant.
  void update(const Eigen::Vector3d& f_meas_mps2, const Eigen::Vector3d& w_meas_radps,
              const Eigen::Vector3d& dw_radps2);

  Eigen::Quaterniond q_b_n() const;
  Eigen::Vector3d gyro_drift_radps() const { return kf_.x().segment<3>(4); }
  /// Lever arm in body axes (zero for kNone; [0 0 l] for kVertical).
  Eigen::Vector3d lever_b_m() const;
  /// 1-sigma of the lever-arm state components in body axes (zero where not estimated).
  Eigen::Vector3d lever_sigma_m() const;
  /// Judged against config.observability_sigma_limit_m.
  LeverArmObservability observability() const;
  int state_size() const { return kf_.size(); }
  /// false once the covariance failed its check (reason in health_reason()); the attitude
  /// is then propagated without further updates.
  bool healthy() const { return kf_.healthy(); }
  const std::string& health_reason() const { return kf_.reason(); }

 private:
  using Filter = KalmanFilter<Eigen::Dynamic>;
  static Filter make_filter(const LeverArmEkfConfig& config, const Eigen::Quaterniond& q_b_n0);
  Eigen::Matrix3d lever_matrix(const Eigen::Vector3d& w_meas_radps, const Eigen::Vector3d& dw_radps2) const;
  LeverArmEkfConfig config_;
  int lever_states_ = 0;
  Filter kf_;  ///< x = [q (4), mu (3), L (lever_states_)]
  Eigen::Matrix3d information_ = Eigen::Matrix3d::Zero();
};

/// Angular acceleration from sampled rates by a centred local-linear fit over
/// +-half_window samples (a zero-lag smoother; in real time it costs half_window samples of
/// latency). Ends use the samples available.
std::vector<Eigen::Vector3d> smoothed_angular_acceleration(const std::vector<Eigen::Vector3d>& w_radps, double dt_s,
                                                           int half_window);

/// Filter outputs over a run.
struct LeverArmEkfRun {
  std::vector<double> t_s;
  std::vector<double> roll_rad;
  std::vector<Eigen::Vector3d> lever_b_m;
  Eigen::Vector3d final_lever_sigma_m = Eigen::Vector3d::Zero();
  LeverArmObservability observability;
};

/// Runs the filter over uniformly spaced readings. The initial attitude is levelled from the
/// mean specific force of the first level_samples readings (yaw 0: MEMS gyros cannot find
/// north). Throws std::invalid_argument on fewer than 2 readings or non-finite data.
LeverArmEkfRun run_lever_arm_ekf(const std::vector<ImuReading>& imu, const LeverArmEkfConfig& config,
                                 int level_samples = 50, int accel_half_window = 5);

}  // namespace deepnav
