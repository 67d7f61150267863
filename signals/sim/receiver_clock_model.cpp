#include "signals/sim/receiver_clock_model.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav {

ReceiverClockModel::ReceiverClockModel(double bias_s, double drift_sps, double h0, double h_minus2, std::uint64_t seed)
    : state_{bias_s, drift_sps}, s_bias_(h0 / 2.0), s_drift_(2.0 * M_PI * M_PI * h_minus2), rng_(seed) {}

const ClockState& ReceiverClockModel::step(double dt) {
  // Process noise covariance of the exact discretisation:
  // Q = [S_b dt + S_d dt^3/3, S_d dt^2/2; S_d dt^2/2, S_d dt]; sampled with its Cholesky factor.
  const double q11 = s_bias_ * dt + s_drift_ * dt * dt * dt / 3.0;
  const double q12 = s_drift_ * dt * dt / 2.0;
  const double q22 = s_drift_ * dt;
  const double z1 = normal_(rng_);
  const double z2 = normal_(rng_);
  double w_bias = 0.0, w_drift = 0.0;
  if (q11 > 0.0) {
    const double l11 = std::sqrt(q11);
    const double l21 = q12 / l11;
    const double l22 = std::sqrt(std::max(0.0, q22 - l21 * l21));
    w_bias = l11 * z1;
    w_drift = l21 * z1 + l22 * z2;
  }
  state_.bias_s += state_.drift_sps * dt + w_bias;
  state_.drift_sps += w_drift;
  return state_;
}

}  // namespace deepnav
