#include "receiver/mitigation/mitigation_notch.hpp"

#include <cmath>

namespace deepnav {
namespace {
/// Samples over which the pole section's power is averaged for the step normalisation.
constexpr double kPowerAveragingSamples = 256.0;
}  // namespace

AdaptiveNotch::AdaptiveNotch(const MitigationConfig& config, double sample_rate_hz)
    : pole_radius_(config.notch_pole_radius), step_(config.notch_step), power_alpha_(1.0 / kPowerAveragingSamples) {
  validate_mitigation(config, sample_rate_hz);
}

void AdaptiveNotch::reset() {
  z0_ = {0.0, 0.0};
  previous_ar_ = {0.0, 0.0};
  power_ar_ = 0.0;
}

void AdaptiveNotch::process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) {
  for (std::size_t k = 0; k < in.size(); ++k) {
    const std::complex<double> x(in[k]);
    const std::complex<double> ar = x + pole_radius_ * z0_ * previous_ar_;
    const std::complex<double> y = ar - z0_ * previous_ar_;
    power_ar_ += power_alpha_ * (std::norm(ar) - power_ar_);
    if (power_ar_ > 0.0) z0_ += step_ * y * std::conj(previous_ar_) / power_ar_;
    // A zero outside the unit circle would put the pole outside it too once k_a |z0| > 1.
    if (const double r = std::abs(z0_); r > 1.0) z0_ /= r;
    previous_ar_ = ar;
    out[k] = std::complex<float>(y);
  }
}

}  // namespace deepnav
