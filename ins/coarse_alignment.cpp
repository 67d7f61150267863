#include "ins/coarse_alignment.hpp"
#include "ins/frames.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

constexpr double kRadpsToDegph = 180.0 / std::numbers::pi * 3600.0;

double wrap_two_pi(double angle_rad) {
  const double wrapped = std::fmod(angle_rad, 2.0 * std::numbers::pi);
  const double positive = wrapped < 0.0 ? wrapped + 2.0 * std::numbers::pi : wrapped;
  return positive >= 2.0 * std::numbers::pi ? 0.0 : positive;  // -tiny + 2 pi rounds to 2 pi
}

AlignedAttitude attitude_from_dcm(const Eigen::Matrix3d& C_b_n) {
  AlignedAttitude out;
  out.C_b_n = C_b_n;
  out.roll_rad = std::atan2(C_b_n(2, 1), C_b_n(2, 2));
  out.pitch_rad = std::asin(std::clamp(-C_b_n(2, 0), -1.0, 1.0));
  out.yaw_rad = wrap_two_pi(std::atan2(C_b_n(1, 0), C_b_n(0, 0)));
  return out;
}

Eigen::Matrix3d dcm_from_euler(double roll_rad, double pitch_rad, double yaw_rad) {
  return (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// Nearest rotation matrix (polar decomposition); flips the last singular vector if
/// needed so that the result is proper.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& M) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

/// Short number for messages ("%.4g").
std::string num(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

void require_finite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) throw std::invalid_argument(std::string("coarse alignment: ") + what + " is not finite");
}

}  // namespace

AlignedAttitude align_two_step(const Eigen::Vector3d& f_b_mps2, const Eigen::Vector3d& w_ib_b_radps) {
  require_finite(f_b_mps2, "specific force f_b");
  require_finite(w_ib_b_radps, "angular rate w_ib_b");
  if (f_b_mps2.norm() <= 0.0) throw std::invalid_argument("two-step alignment: specific force f_b is zero");
  // Step 1, levelling (paper 000 [docs/references.md], eqs. 10-11): f_b = C_n^b [0 0 -g], so f_y = -g sin(roll) cos(pitch),
  // f_z = -g cos(roll) cos(pitch), f_x = g sin(pitch). atan2 with the signs keeps any roll.
  const double roll = std::atan2(-f_b_mps2.y(), -f_b_mps2.z());
  const double pitch = std::atan2(f_b_mps2.x(), std::hypot(f_b_mps2.y(), f_b_mps2.z()));
  // Step 2, gyrocompassing (eqs. 15-17): level the gyro vector, w_level = C1^T w_b = C2 w_n,
  // whose first two components are w_N cos(yaw) and -w_N sin(yaw).
  const Eigen::Matrix3d C_level_b = dcm_from_euler(roll, pitch, 0.0);
  const Eigen::Vector3d w_level = C_level_b * w_ib_b_radps;
  if (std::hypot(w_level.x(), w_level.y()) <= 0.0)
    throw std::invalid_argument("two-step alignment: no horizontal Earth rate (at a pole), yaw undefined");
  const double yaw = std::atan2(-w_level.y(), w_level.x());
  return attitude_from_dcm(dcm_from_euler(roll, pitch, yaw));
}

OneShotAlignment align_one_shot(const Eigen::Vector3d& f_b_mps2, const Eigen::Vector3d& w_ib_b_radps, double lat_rad,
                                double gravity_mps2) {
  require_finite(f_b_mps2, "specific force f_b");
  require_finite(w_ib_b_radps, "angular rate w_ib_b");
  if (std::abs(std::cos(lat_rad)) < 1e-6)
    throw std::invalid_argument("one-shot alignment: latitude at a pole, heading undefined");
  const Eigen::Vector3d f_n(0.0, 0.0, -gravity_mps2);
  const Eigen::Vector3d w_n = earth_rate_ned_radps(lat_rad);
  Eigen::Matrix3d nav_rows;  // paper eq. 4: rows are f^T, w^T, (f x w)^T
  nav_rows << f_n.transpose(), w_n.transpose(), f_n.cross(w_n).transpose();
  Eigen::Matrix3d body_rows;
  body_rows << f_b_mps2.transpose(), w_ib_b_radps.transpose(), f_b_mps2.cross(w_ib_b_radps).transpose();
  OneShotAlignment out;
  out.raw_C_b_n = nav_rows.inverse() * body_rows;  // eq. 5
  out.attitude = attitude_from_dcm(nearest_rotation(out.raw_C_b_n));
  return out;
}

Eigen::Vector3d tilt_error_ned_rad(const Eigen::Matrix3d& C_b_n_est, const Eigen::Matrix3d& C_b_n_true) {
  const Eigen::Matrix3d E = C_b_n_est * C_b_n_true.transpose();
  const Eigen::Matrix3d skew = 0.5 * (E - E.transpose());
  return {skew(2, 1), skew(0, 2), skew(1, 0)};
}

Eigen::Vector3d one_shot_tilt_error_rad(const Eigen::Vector3d& df_n_mps2, const Eigen::Vector3d& dw_n_radps,
                                        double lat_rad, double gravity_mps2) {
  const double g = gravity_mps2;
  const double w_ie = wgs84::kEarthRate_radps;
  const double tan_l = std::tan(lat_rad);
  const double sec_l = 1.0 / std::cos(lat_rad);
  return {-df_n_mps2.y() / g, 0.5 * (df_n_mps2.x() / g - df_n_mps2.z() / g * tan_l + dw_n_radps.z() / w_ie * sec_l),
          df_n_mps2.y() / g * tan_l - dw_n_radps.y() / w_ie * sec_l};
}

Eigen::Vector3d two_step_tilt_error_rad(const Eigen::Vector3d& df_n_mps2, const Eigen::Vector3d& dw_n_radps,
                                        double lat_rad, double gravity_mps2, bool include_leveling_coupling) {
  const double g = gravity_mps2;
  const double sec_l = 1.0 / std::cos(lat_rad);
  double eps_d = -dw_n_radps.y() / wgs84::kEarthRate_radps * sec_l;
  if (include_leveling_coupling) eps_d += df_n_mps2.y() / g * std::tan(lat_rad);
  return {-df_n_mps2.y() / g, df_n_mps2.x() / g, eps_d};
}

StaticImuMean stationary_imu_outputs(const Eigen::Matrix3d& C_b_n, double lat_rad, double gravity_mps2) {
  StaticImuMean out;
  out.f_b_mps2 = C_b_n.transpose() * Eigen::Vector3d(0.0, 0.0, -gravity_mps2);
  out.w_ib_b_radps = C_b_n.transpose() * earth_rate_ned_radps(lat_rad);
  return out;
}

StationarityReport check_stationary(std::span<const Eigen::Vector3d> f_b_mps2,
                                    std::span<const Eigen::Vector3d> w_ib_b_radps, double gravity_mps2,
                                    const StationarityLimits& limits) {
  if (f_b_mps2.size() != w_ib_b_radps.size())
    throw std::invalid_argument("stationarity check: " + std::to_string(f_b_mps2.size()) +
                                " accelerometer samples but " + std::to_string(w_ib_b_radps.size()) + " gyro samples");
  if (f_b_mps2.size() < 2) throw std::invalid_argument("stationarity check: need at least 2 samples of f_b and w_ib_b");
  const auto n = static_cast<double>(f_b_mps2.size());
  StationarityReport report;
  for (std::size_t i = 0; i < f_b_mps2.size(); ++i) {
    if (!f_b_mps2[i].allFinite() || !w_ib_b_radps[i].allFinite())
      throw std::invalid_argument("stationarity check: sample " + std::to_string(i) + " is not finite");
    report.mean.f_b_mps2 += f_b_mps2[i] / n;
    report.mean.w_ib_b_radps += w_ib_b_radps[i] / n;
  }
  Eigen::Vector3d var_f = Eigen::Vector3d::Zero();
  Eigen::Vector3d var_w = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < f_b_mps2.size(); ++i) {
    var_f += (f_b_mps2[i] - report.mean.f_b_mps2).cwiseAbs2() / (n - 1.0);
    var_w += (w_ib_b_radps[i] - report.mean.w_ib_b_radps).cwiseAbs2() / (n - 1.0);
  }
  report.accel_norm_error_mps2 = report.mean.f_b_mps2.norm() - gravity_mps2;
  report.accel_std_mps2 = std::sqrt(var_f.maxCoeff());
  report.gyro_std_radps = std::sqrt(var_w.maxCoeff());
  report.gyro_mean_norm_radps = report.mean.w_ib_b_radps.norm();

  // Sample std tolerance: the configured ratio, widened by the estimator's own spread.
  const double std_slack = limits.noise_ratio_limit * (1.0 + 3.0 / std::sqrt(2.0 * (n - 1.0)));
  // Floors keep noise-free (simulated) data from failing on rounding.
  const double accel_std_max = std::max(std_slack * limits.accel_noise_mps2, 1e-9);
  const double gyro_std_max = std::max(std_slack * limits.gyro_noise_radps, 1e-12);
  // The mean itself is uncertain by noise/sqrt(n); allow 5 sigma of that on top of the bias.
  const double norm_tol = limits.accel_bias_mps2 + 5.0 * limits.accel_noise_mps2 / std::sqrt(n);
  const double rate_max =
      wgs84::kEarthRate_radps + limits.gyro_bias_radps + 5.0 * limits.gyro_noise_radps / std::sqrt(n);

  std::string reason;
  auto add = [&reason](const std::string& text) { reason += (reason.empty() ? "" : "; ") + text; };
  if (std::abs(report.accel_norm_error_mps2) > norm_tol)
    add("accelerometer mean norm " + num(report.mean.f_b_mps2.norm()) + " m/s^2 differs from gravity " +
        num(gravity_mps2) + " m/s^2 by more than " + num(norm_tol));
  if (report.gyro_mean_norm_radps > rate_max)
    add("mean angular rate " + num(report.gyro_mean_norm_radps * kRadpsToDegph) +
        " deg/h exceeds Earth rate plus gyro bias (" + num(rate_max * kRadpsToDegph) + " deg/h)");
  if (report.accel_std_mps2 > accel_std_max)
    add("accelerometer sample std " + num(report.accel_std_mps2) + " m/s^2 exceeds the " + num(accel_std_max) +
        " m/s^2 expected at rest");
  if (report.gyro_std_radps > gyro_std_max)
    add("gyro sample std " + num(report.gyro_std_radps) + " rad/s exceeds the " + num(gyro_std_max) +
        " rad/s expected at rest");
  report.stationary = reason.empty();
  report.reason = report.stationary ? std::string{} : "not stationary: " + reason;
  return report;
}

CoarseAlignmentOutcome coarse_align(std::span<const Eigen::Vector3d> f_b_mps2,
                                    std::span<const Eigen::Vector3d> w_ib_b_radps, double lat_rad, double gravity_mps2,
                                    CoarseAlignmentMethod method, const StationarityLimits& limits) {
  CoarseAlignmentOutcome out;
  out.stationarity = check_stationary(f_b_mps2, w_ib_b_radps, gravity_mps2, limits);
  if (!out.stationarity.stationary) return out;
  const StaticImuMean& mean = out.stationarity.mean;
  out.attitude = method == CoarseAlignmentMethod::kTwoStep
                     ? align_two_step(mean.f_b_mps2, mean.w_ib_b_radps)
                     : align_one_shot(mean.f_b_mps2, mean.w_ib_b_radps, lat_rad, gravity_mps2).attitude;
  return out;
}

}  // namespace deepnav
