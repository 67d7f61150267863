#pragma once
// Stationary coarse alignment (paper 000 [docs/references.md]): the two-step method (roll and pitch
// from the accelerometers, then yaw from the levelled gyro vector) and Britting's
// one-shot method (C_b^n from f, w and f x w at once), the analytic tilt-error
// formulas of the paper's Table 1, and a stationarity check that refuses to
// align data taken on a moving vehicle.
//
// Conventions: NED navigation frame, body x forward / y right / z down,
// C_b_n = Rz(yaw) Ry(pitch) Rx(roll). Sensor errors are "measured minus true".
// Tilt error eps (NED, radians) is defined by C_b_n_est = (I + [eps x]) C_b_n_true,
// i.e. eps_D equals the yaw error and, near level, eps_N/eps_E equal the
// roll/pitch errors (paper eq. 35).
#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>

namespace deepnav {

/// Attitude from an alignment. C_b_n is always a proper rotation.
struct AlignedAttitude {
  Eigen::Matrix3d C_b_n = Eigen::Matrix3d::Identity();
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;  ///< in [0, 2*pi)
};

/// Two-step alignment from the averaged specific force and angular rate at rest.
/// Any roll (|pitch| < 90 deg) and any heading. Throws std::invalid_argument when
/// f_b is zero or the levelled Earth rate has no horizontal component (at a pole).
AlignedAttitude align_two_step(const Eigen::Vector3d& f_b_mps2, const Eigen::Vector3d& w_ib_b_radps);

/// Britting's one-shot alignment: C_b^n = [f_n; w_n; (f x w)_n]^-1 [f_b; w_b; (f x w)_b]
/// (rows are transposed vectors), with g the local gravity magnitude. The raw matrix is
/// not orthogonal when the sensors have errors; it is returned in raw_C_b_n and its
/// nearest rotation (polar decomposition) in the attitude.
struct OneShotAlignment {
  AlignedAttitude attitude;
  Eigen::Matrix3d raw_C_b_n = Eigen::Matrix3d::Identity();
};
OneShotAlignment align_one_shot(const Eigen::Vector3d& f_b_mps2, const Eigen::Vector3d& w_ib_b_radps, double lat_rad,
                                double gravity_mps2);

/// Tilt error eps with C_est = (I + [eps x]) C_true, from the skew part of C_est C_true^T - I
/// (the symmetric part, the one-shot matrix's non-orthogonality, is ignored).
Eigen::Vector3d tilt_error_ned_rad(const Eigen::Matrix3d& C_b_n_est, const Eigen::Matrix3d& C_b_n_true);

/// Analytic first-order tilt errors (paper 000 Table 1) from the sensor errors expressed
/// in NED (df_n = C_b_n df_b, dw_n = C_b_n dw_b).
///
/// Sign note: with the "measured minus true" sensor errors and the tilt defined above,
/// a direct linearisation gives the gyro terms the opposite sign to the paper's Table 1
/// (the paper's own eq. 36 has the two-step sign we use); magnitudes agree.
///   one-shot: eps_N = -df_E/g
///             eps_E = 1/2 [df_N/g - (df_D/g) tan L + (dw_D/w_ie) sec L]
///             eps_D = (df_E/g) tan L - (dw_E/w_ie) sec L
///   two-step: eps_N = -df_E/g, eps_E = df_N/g,
///             eps_D = -(dw_E/w_ie) sec L  [+ (df_E/g) tan L when include_leveling_coupling]
/// The paper drops the two-step (df_E/g) tan L term (its eq. 31 neglects the
/// accelerometer's influence on yaw): the mis-levelled frame leaks the vertical Earth
/// rate into the east axis. It matters when gyro errors are small.
Eigen::Vector3d one_shot_tilt_error_rad(const Eigen::Vector3d& df_n_mps2, const Eigen::Vector3d& dw_n_radps,
                                        double lat_rad, double gravity_mps2);
Eigen::Vector3d two_step_tilt_error_rad(const Eigen::Vector3d& df_n_mps2, const Eigen::Vector3d& dw_n_radps,
                                        double lat_rad, double gravity_mps2, bool include_leveling_coupling = true);

/// Ideal stationary sensor outputs for a body at attitude C_b_n at latitude lat.
struct StaticImuMean {
  Eigen::Vector3d f_b_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_ib_b_radps = Eigen::Vector3d::Zero();
};
StaticImuMean stationary_imu_outputs(const Eigen::Matrix3d& C_b_n, double lat_rad, double gravity_mps2);

/// What a sensor at rest is expected to show, per sample.
struct StationarityLimits {
  double accel_noise_mps2 = 0.0;   ///< 1-sigma white noise of one accelerometer sample
  double gyro_noise_radps = 0.0;   ///< 1-sigma white noise of one gyro sample
  double accel_bias_mps2 = 0.05;   ///< largest plausible accelerometer bias + gravity model error (norm check)
  double gyro_bias_radps = 1e-4;   ///< largest plausible gyro bias (mean-rate check)
  double noise_ratio_limit = 3.0;  ///< allowed sample std / expected std (vibration, engine)
};

/// Result of the rest check on raw samples; reason is empty when stationary.
struct StationarityReport {
  bool stationary = false;
  std::string reason;
  double accel_norm_error_mps2 = 0.0;  ///< |mean f| - g
  double accel_std_mps2 = 0.0;         ///< largest per-axis sample std
  double gyro_std_radps = 0.0;         ///< largest per-axis sample std
  double gyro_mean_norm_radps = 0.0;   ///< |mean w|
  StaticImuMean mean;
};

/// Checks raw samples (same length, at least 2) against rest: |mean f| close to g, mean rate
/// no larger than Earth rate plus bias, and per-axis sample spread consistent with the
/// sensor noise. Throws std::invalid_argument on empty/mismatched/non-finite input.
StationarityReport check_stationary(std::span<const Eigen::Vector3d> f_b_mps2,
                                    std::span<const Eigen::Vector3d> w_ib_b_radps, double gravity_mps2,
                                    const StationarityLimits& limits);

enum class CoarseAlignmentMethod { kTwoStep, kOneShot };

/// Alignment from raw samples: the attitude only when the rest check passes, otherwise
/// std::nullopt with the report saying why (never a confident attitude from moving data).
struct CoarseAlignmentOutcome {
  StationarityReport stationarity;
  std::optional<AlignedAttitude> attitude;
};
CoarseAlignmentOutcome coarse_align(std::span<const Eigen::Vector3d> f_b_mps2,
                                    std::span<const Eigen::Vector3d> w_ib_b_radps, double lat_rad, double gravity_mps2,
                                    CoarseAlignmentMethod method, const StationarityLimits& limits);

}  // namespace deepnav
