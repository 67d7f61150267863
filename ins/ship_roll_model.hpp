#pragma once
// Angular-motion scenarios of paper 004 [docs/references.md] (attitude with a lever arm): a small vessel
// rolled by an external moment, the single-axis rate table, and a multi-axis
// oscillation (rich motion for estimating a 3-D lever arm). Each produces the true
// attitude, body rate and angular acceleration at a fixed sample rate; the centre of
// gravity (rotation centre) does not translate.
#include <Eigen/Core>
#include <vector>

namespace deepnav {

/// True rotational state at one sample.
struct AttitudeTruth {
  double t_s = 0.0;
  Eigen::Matrix3d C_b_n = Eigen::Matrix3d::Identity();  ///< body -> NED
  Eigen::Vector3d w_nb_b_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d dw_nb_b_radps2 = Eigen::Vector3d::Zero();
  double roll_rad = 0.0;
};

/// One-degree-of-freedom roll of a ~7 t vessel: I phi'' + c phi' + k phi = M(t), with a
/// sinusoidal wave moment M(t) = M0 sin(2 pi (t - t0) / T) applied between t0 and t1.
/// The paper gives the mass and the 5-15 s window only; the hull figures below are
/// ours (3 m beam, 0.5 m metacentric height, radius of gyration 1.2 m, 10 % damping)
/// and give a roll period of about 3.4 s and a roll of about 11 deg at the 4 s wave.
struct ShipRollParameters {
  double mass_kg = 7000.0;
  double roll_inertia_kgm2 = 7000.0 * 1.2 * 1.2;
  double metacentric_height_m = 0.5;
  double damping_ratio = 0.1;
  double gravity_mps2 = 9.80665;
  double moment_amplitude_Nm = 2000.0;
  double moment_period_s = 4.0;
  double moment_start_s = 5.0;
  double moment_end_s = 15.0;
  double duration_s = 20.0;
  double sample_rate_hz = 100.0;
};
/// Integrates the roll equation (RK4, 10 substeps per sample). Throws std::invalid_argument
/// on non-positive inertia, restoring stiffness, duration or rate.
std::vector<AttitudeTruth> simulate_ship_roll(const ShipRollParameters& params);

/// Single-axis rate table about body x: roll = A sin(2 pi (t - t0) / T) from t0 on, with the
/// amplitude ramped in over ramp_s (a real table does not jump to full rate).
struct RateTableParameters {
  double amplitude_rad = 30.0 * 3.14159265358979323846 / 180.0;
  double period_s = 2.0;
  double start_s = 5.0;
  double ramp_s = 1.0;
  double duration_s = 20.0;
  double sample_rate_hz = 100.0;
};
std::vector<AttitudeTruth> simulate_rate_table(const RateTableParameters& params);

/// Roll, pitch and yaw each oscillating: angle_k = A_k sin(2 pi t / T_k + phase_k).
struct EulerOscillationParameters {
  Eigen::Vector3d amplitude_rad = Eigen::Vector3d::Zero();
  Eigen::Vector3d period_s = Eigen::Vector3d::Ones();
  Eigen::Vector3d phase_rad = Eigen::Vector3d::Zero();
  double duration_s = 30.0;
  double sample_rate_hz = 100.0;
};
std::vector<AttitudeTruth> simulate_euler_oscillation(const EulerOscillationParameters& params);

}  // namespace deepnav
