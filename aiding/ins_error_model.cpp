#include "aiding/ins_error_model.hpp"

#include <cmath>

#include "ins/frames.hpp"
#include "ins/rotations.hpp"
#include "ins/wgs84.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kC = wgs84::kSpeedOfLight_mps;

/// PSD of a triad's bias process: 2 sigma^2 / tau for a Gauss-Markov bias; without a
/// correlation time, the instability spread over an hour as a random walk.
double bias_psd(const TriadErrorSpec& spec) {
  const double sigma = spec.bias_instability_sigma;
  if (spec.bias_correlation_time_s > 0.0) return 2.0 * sigma * sigma / spec.bias_correlation_time_s;
  return sigma * sigma / 3600.0;
}

}  // namespace

ProcessNoise process_noise_from(const ImuErrorModel& imu, const OscillatorNoise& oscillator) {
  ProcessNoise q;
  const double vrw2 = imu.accel.random_walk * imu.accel.random_walk;
  const double arw2 = imu.gyro.random_walk * imu.gyro.random_walk;
  q.psd.segment<3>(kVel).setConstant(vrw2);
  q.psd.segment<3>(kAtt).setConstant(arw2);
  q.psd.segment<3>(kAccelBias).setConstant(bias_psd(imu.accel));
  q.psd.segment<3>(kGyroBias).setConstant(bias_psd(imu.gyro));
  q.psd(kClockBias) = kC * kC * oscillator.h0 / 2.0;
  q.psd(kClockDrift) = kC * kC * 2.0 * M_PI * M_PI * oscillator.hm2;
  q.accel_bias_tau_s = imu.accel.bias_correlation_time_s;
  q.gyro_bias_tau_s = imu.gyro.bias_correlation_time_s;
  return q;
}

StateMatrix error_dynamics(const NavState& state, const Eigen::Vector3d& f_b_mps2, const ProcessNoise& noise) {
  StateMatrix F = StateMatrix::Zero();
  const Eigen::Matrix3d C_b_n = state.q_b_n.toRotationMatrix();
  const Eigen::Vector3d w_ie = earth_rate_ned_radps(state.llh.lat_rad);
  const Eigen::Vector3d w_en = transport_rate_ned_radps(state.llh, state.v_ned_mps);
  const Eigen::Vector3d f_n = C_b_n * f_b_mps2;
  const double radius =
      std::sqrt(wgs84::meridian_radius_m(state.llh.lat_rad) * wgs84::transverse_radius_m(state.llh.lat_rad)) +
      state.llh.height_m;
  const double g = wgs84::normal_gravity_mps2(state.llh.lat_rad, state.llh.height_m);

  F.block<3, 3>(kPos, kVel).setIdentity();
  F.block<3, 3>(kVel, kAtt) = -skew(f_n);
  F.block<3, 3>(kVel, kAccelBias) = C_b_n;
  F.block<3, 3>(kVel, kVel) = -skew(2.0 * w_ie + w_en);
  F(kVel + 2, kPos + 2) = 2.0 * g / radius;  // gravity grows as the height falls
  F.block<3, 3>(kAtt, kAtt) = -skew(w_ie + w_en);
  F.block<3, 3>(kAtt, kGyroBias) = C_b_n;
  if (noise.accel_bias_tau_s > 0.0)
    F.block<3, 3>(kAccelBias, kAccelBias) = -Eigen::Matrix3d::Identity() / noise.accel_bias_tau_s;
  if (noise.gyro_bias_tau_s > 0.0)
    F.block<3, 3>(kGyroBias, kGyroBias) = -Eigen::Matrix3d::Identity() / noise.gyro_bias_tau_s;
  F(kClockBias, kClockDrift) = 1.0;
  return F;
}

void discretize(const StateMatrix& F, const ProcessNoise& noise, double dt_s, StateMatrix& Phi, StateMatrix& Qd) {
  const StateMatrix Fdt = F * dt_s;
  Phi = StateMatrix::Identity() + Fdt + 0.5 * Fdt * Fdt;
  const StateMatrix Q = noise.psd.asDiagonal();
  Qd = 0.5 * (Phi * Q * Phi.transpose() + Q) * dt_s;
}

}  // namespace deepnav::aiding
