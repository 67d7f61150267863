#pragma once
// Receiver oscillator: bias b (s) and drift d (s/s) driven by the two-state random
// walk of Brown & Hwang: b' = d + w_b, d' = w_d, with spectral densities
// S_b = h0/2 and S_d = 2 pi^2 h_-2 (white frequency and random-walk frequency noise).
#include <cstdint>
#include <random>

namespace deepnav {

struct ClockState {
  double bias_s = 0.0;
  double drift_sps = 0.0;
};

class ReceiverClockModel {
 public:
  ReceiverClockModel(double bias_s, double drift_sps, double h0, double h_minus2, std::uint64_t seed);
  /// Advances by dt seconds (exact discretisation of the two-state model) and returns the new state.
  const ClockState& step(double dt_s);
  const ClockState& state() const { return state_; }

 private:
  ClockState state_;
  double s_bias_;   ///< S_b, s^2/s
  double s_drift_;  ///< S_d, (s/s)^2/s
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace deepnav
