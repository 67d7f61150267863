#include "ins/fine_alignment.hpp"
#include "ins/frames.hpp"
#include "ins/rotations.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ins/coarse_alignment.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

Eigen::Matrix<double, 12, 12> initial_covariance(const FineAlignmentConfig& config) {
  Eigen::Matrix<double, 12, 12> P = Eigen::Matrix<double, 12, 12>::Zero();
  const double tilt2 = config.initial_tilt_sigma_rad * config.initial_tilt_sigma_rad;
  P.diagonal().segment<3>(0) << tilt2, tilt2, config.initial_heading_sigma_rad * config.initial_heading_sigma_rad;
  P.diagonal().segment<3>(3).setConstant(1e-6);  // starts at rest, v = 0
  P.diagonal().segment<3>(6).setConstant(config.accel_bias_sigma_mps2 * config.accel_bias_sigma_mps2);
  P.diagonal().segment<3>(9).setConstant(config.gyro_bias_sigma_radps * config.gyro_bias_sigma_radps);
  return P;
}

}  // namespace

double gyrocompass_heading_limit_rad(double dw_east_radps, double lat_rad) {
  return -dw_east_radps / (wgs84::kEarthRate_radps * std::cos(lat_rad));
}

FineAlignment::FineAlignment(const FineAlignmentConfig& config, const Eigen::Matrix3d& C_b_n0)
    : config_(config),
      C_b_n_(C_b_n0),
      kf_(Filter::Vector::Zero(), initial_covariance(config), {.allow_zero_variance = true}) {
  if (!(config.zupt_interval_s > 0.0)) throw std::invalid_argument("fine alignment: zupt_interval_s must be positive");
  if (!(config.zupt_sigma_mps > 0.0)) throw std::invalid_argument("fine alignment: zupt_sigma_mps must be positive");
  if (!C_b_n0.allFinite()) throw std::invalid_argument("fine alignment: initial C_b_n is not finite");
}

void FineAlignment::step(const ImuReading& reading, double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("fine alignment: step dt must be positive");
  if (!reading.f_b_mps2.allFinite() || !reading.w_ib_b_radps.allFinite())
    throw std::invalid_argument("fine alignment: reading at t = " + std::to_string(reading.t_s) + " s is not finite");
  if (samples_per_zupt_ == 0) samples_per_zupt_ = std::max(1L, std::lround(config_.zupt_interval_s / dt_s));
  const Eigen::Vector3d w_ie_n = earth_rate_ned_radps(config_.lat_rad);
  // Attitude: body rotation on the right, Earth rotation of the NED frame on the left.
  C_b_n_ = dcm_from_rotation_vector(-w_ie_n * dt_s) * C_b_n_ *
           dcm_from_rotation_vector((reading.w_ib_b_radps - gyro_bias_radps_) * dt_s);
  const Eigen::Vector3d f_n = C_b_n_ * (reading.f_b_mps2 - accel_bias_mps2_);
  const Eigen::Vector3d g_n(0.0, 0.0, config_.gravity_mps2);
  v_ned_mps_ += (f_n + g_n - 2.0 * w_ie_n.cross(v_ned_mps_)) * dt_s;
  time_since_zupt_s_ += dt_s;
  if (++samples_since_zupt_ >= samples_per_zupt_) zupt();
}

void FineAlignment::zupt() {
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  const double T = time_since_zupt_s_;
  // At rest the true specific force is [0 0 -g]. Linearising about the measured (noisy)
  // f_n instead would let accelerometer noise pose as horizontal manoeuvres and make
  // heading look observable beyond the gyrocompass limit (overconfident, biased).
  const Eigen::Vector3d f_n(0.0, 0.0, -config_.gravity_mps2);
  const Eigen::Vector3d w_ie_n = earth_rate_ned_radps(config_.lat_rad);
  Mat12 F = Mat12::Zero();
  F.block<3, 3>(0, 0) = -skew(w_ie_n);
  F.block<3, 3>(0, 9) = -Eigen::Matrix3d::Identity();  // bias errors resolved in NED (see header)
  F.block<3, 3>(3, 0) = skew(f_n);
  F.block<3, 3>(3, 3) = -2.0 * skew(w_ie_n);
  F.block<3, 3>(3, 6) = Eigen::Matrix3d::Identity();
  const Mat12 FT = F * T;
  const Mat12 Phi = Mat12::Identity() + FT + 0.5 * FT * FT;
  Mat12 Qd = Mat12::Zero();
  const double gyro_psd = config_.gyro_noise_density_radps_per_rthz * config_.gyro_noise_density_radps_per_rthz;
  const double accel_psd = config_.accel_noise_density_mps2_per_rthz * config_.accel_noise_density_mps2_per_rthz;
  Qd.diagonal().segment<3>(0).setConstant(gyro_psd * T);
  Qd.diagonal().segment<3>(3).setConstant(accel_psd * T);
  kf_.predict(Phi, Qd);  // the error state is zero between updates (fed back)

  // ZUPT: z = v_est - 0 = dv.
  const double r = config_.zupt_sigma_mps * config_.zupt_sigma_mps;
  Eigen::Matrix<double, 3, 12> H = Eigen::Matrix<double, 3, 12>::Zero();
  H.block<3, 3>(0, 3).setIdentity();
  if (kf_.update(v_ned_mps_, H, Eigen::Vector3d::Constant(r)).applied) {
    // Closed loop: C_true = (I + [phi x]) C_est, v -= dv, biases += their errors.
    const Filter::Vector dx = kf_.x();
    C_b_n_ = dcm_from_rotation_vector(dx.segment<3>(0)) * C_b_n_;
    v_ned_mps_ -= dx.segment<3>(3);
    accel_bias_mps2_ += C_b_n_.transpose() * dx.segment<3>(6);
    gyro_bias_radps_ += C_b_n_.transpose() * dx.segment<3>(9);
    kf_.clear_state();
  }

  time_since_zupt_s_ = 0.0;
  samples_since_zupt_ = 0;
}

Eigen::Vector3d FineAlignment::attitude_sigma_rad() const { return kf_.P().diagonal().segment<3>(0).cwiseSqrt(); }

FineAlignmentTrace run_fine_alignment(const std::vector<ImuReading>& imu, const FineAlignmentConfig& config,
                                      const Eigen::Matrix3d& C_b_n0, const Eigen::Matrix3d& C_b_n_true,
                                      double trace_interval_s) {
  if (imu.size() < 2) throw std::invalid_argument("fine alignment run: need at least 2 IMU readings");
  const double dt = imu[1].t_s - imu[0].t_s;
  if (!(dt > 0.0)) throw std::invalid_argument("fine alignment run: readings must have increasing time");
  const long every = std::max(1L, std::lround(trace_interval_s / dt));
  FineAlignment filter(config, C_b_n0);
  FineAlignmentTrace trace;
  for (std::size_t k = 1; k < imu.size(); ++k) {
    filter.step(imu[k], imu[k].t_s - imu[k - 1].t_s);
    if (static_cast<long>(k) % every == 0) {
      trace.t_s.push_back(imu[k].t_s);
      trace.tilt_error_rad.push_back(tilt_error_ned_rad(filter.C_b_n(), C_b_n_true));
      trace.attitude_sigma_rad.push_back(filter.attitude_sigma_rad());
    }
  }
  return trace;
}

double heading_settling_time_s(const FineAlignmentTrace& trace, double target_rad, double tolerance_rad) {
  if (trace.t_s.empty()) return std::numeric_limits<double>::infinity();
  for (std::size_t i = trace.t_s.size(); i-- > 0;) {
    if (std::abs(trace.tilt_error_rad[i].z() - target_rad) > tolerance_rad)
      return i + 1 < trace.t_s.size() ? trace.t_s[i + 1] : std::numeric_limits<double>::infinity();
  }
  return trace.t_s.front();
}

}  // namespace deepnav
