#pragma once
// Adaptive complex notch filter for one narrowband interferer (D. Borio, L. Camoriano,
// L. Lo Presti, "Two-pole and multi-pole notch filters: a computationally effective
// solution for GNSS interference detection and mitigation", IEEE Systems Journal 2(1),
// 2008):
//   H(z) = (1 - z0 z^-1) / (1 - k_a z0 z^-1),
// a zero z0 that the filter drives onto the interferer's frequency and a pole just
// inside it (k_a < 1) that keeps the notch narrow. z0 follows the normalised stochastic
// gradient of the output power, z0 += mu y[n] conj(x_ar[n-1]) / P_ar, where x_ar is the
// output of the pole section and P_ar its running power; so it converges at the same
// rate whatever the jammer power, and a swept tone is followed as long as it moves
// slowly against mu fs. With noise alone z0 stays near 0 and H is close to 1.
#include <complex>

#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/mitigation/mitigation_stage.hpp"

namespace deepnav {

class AdaptiveNotch final : public MitigationStage {
 public:
  /// Validates the configuration (std::invalid_argument naming the field).
  AdaptiveNotch(const MitigationConfig& config, double sample_rate_hz);

  std::size_t delay_samples() const override { return 0; }
  void process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) override;
  void reset() override;

  /// Current zero: its angle times fs / 2 pi is the notch frequency, |z0| near 1 when locked.
  std::complex<double> zero() const { return z0_; }

 private:
  double pole_radius_, step_, power_alpha_;
  std::complex<double> z0_{0.0, 0.0};
  std::complex<double> previous_ar_{0.0, 0.0};
  double power_ar_ = 0.0;
};

}  // namespace deepnav
