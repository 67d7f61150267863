#include "ins/sim/imu_error_generator.hpp"

#include <cmath>

namespace deepnav {

ImuErrorGenerator::ImuErrorGenerator(const ImuErrorModel& model, std::uint64_t seed) : rng_(seed) {
  gyro_.spec = model.gyro;
  accel_.spec = model.accel;
  // Fixed draw order (gyro, then accelerometer) keeps runs reproducible per seed.
  draw_turn_on(gyro_);
  draw_turn_on(accel_);
}

Eigen::Vector3d ImuErrorGenerator::gaussian3() {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = normal_(rng_);
  return v;
}

void ImuErrorGenerator::draw_turn_on(Triad& t) {
  t.draw.bias = t.spec.bias + t.spec.bias_sigma * gaussian3();
  t.draw.scale_factor = t.spec.scale_factor_sigma * gaussian3();
  t.draw.misalignment.setZero();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (r != c) t.draw.misalignment(r, c) = t.spec.misalignment_sigma_rad * normal_(rng_);
    }
  }
  t.transfer = Eigen::Matrix3d::Identity() + Eigen::Matrix3d(t.draw.scale_factor.asDiagonal()) + t.draw.misalignment;
  // Start the Gauss-Markov bias in its stationary distribution, not at zero.
  if (t.spec.bias_correlation_time_s > 0.0) t.markov = t.spec.bias_instability_sigma * gaussian3();
}

void ImuErrorGenerator::corrupt(Triad& t, double dt_s, Eigen::Vector3d& increment) {
  Eigen::Vector3d y = t.transfer * increment + (t.draw.bias + t.markov) * dt_s;
  // White rate noise of PSD N^2 integrates to an increment of sigma N*sqrt(dt).
  if (t.spec.random_walk > 0.0) y += t.spec.random_walk * std::sqrt(dt_s) * gaussian3();
  // Exact discretisation of db/dt = -b/tau + w, steady-state sigma kept.
  if (t.spec.bias_correlation_time_s > 0.0 && t.spec.bias_instability_sigma > 0.0) {
    const double phi = std::exp(-dt_s / t.spec.bias_correlation_time_s);
    t.markov = phi * t.markov + t.spec.bias_instability_sigma * std::sqrt(1.0 - phi * phi) * gaussian3();
  }
  // Quantization with the remainder carried to the next sample, as integrating IMUs
  // do: each output is off by less than one LSB but the sum never drifts.
  if (t.spec.quantization > 0.0) {
    const Eigen::Vector3d total = y + t.quantization_residual;
    y = (total / t.spec.quantization).array().round() * t.spec.quantization;
    t.quantization_residual = total - y;
  }
  increment = y;
}

void ImuErrorGenerator::apply(double dt_s, Eigen::Vector3d& dtheta_b_rad, Eigen::Vector3d& dv_b_mps) {
  corrupt(gyro_, dt_s, dtheta_b_rad);
  corrupt(accel_, dt_s, dv_b_mps);
}

}  // namespace deepnav
