#include "receiver/mitigation/mitigation_blanking.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace deepnav {
namespace {
/// Samples used to start the noise estimate.
constexpr std::size_t kInitialSamples = 4096;
}  // namespace

PulseBlanker::PulseBlanker(const MitigationConfig& config, double sample_rate_hz) {
  validate_mitigation(config, sample_rate_hz);
  guard_ = static_cast<std::size_t>(config.blanking_guard_samples);
  threshold_ratio_ = std::pow(10.0, config.blanking_threshold_db / 10.0);
  alpha_ = 1.0 / (config.blanking_noise_time_constant_s * sample_rate_hz);
  reset();
}

void PulseBlanker::reset() {
  delay_line_.assign(guard_, {});
  delay_pos_ = 0;
  position_ = 0;
  zero_until_ = -1;
  // The noise estimate survives a reset: the noise level does not change across a gap.
}

void PulseBlanker::initialize_noise(std::span<const std::complex<float>> in) {
  std::vector<double> p;
  const std::size_t n = std::min(in.size(), kInitialSamples);
  for (std::size_t k = 0; k < n; ++k) p.push_back(std::norm(std::complex<double>(in[k])));
  std::nth_element(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(n / 2), p.end());
  // Median of the exponential power of complex Gaussian noise is ln 2 times its mean; an
  // all-zero start gives one squared sample unit, the smallest non-zero integer power.
  noise_power_ = std::max(p[n / 2] / std::numbers::ln2, 1.0);
}

void PulseBlanker::process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) {
  if (in.empty()) return;
  if (noise_power_ < 0.0) initialize_noise(in);
  for (std::size_t k = 0; k < in.size(); ++k) {
    const std::complex<float> x = in[k];
    const double p = std::norm(std::complex<double>(x));
    if (p > threshold_ratio_ * noise_power_) {
      zero_until_ = position_ + static_cast<std::int64_t>(guard_);
    } else {
      noise_power_ += alpha_ * (p - noise_power_);
    }
    // The output now is the input guard_ samples ago.
    std::complex<float> delayed = x;
    if (guard_ > 0) {
      delayed = delay_line_[delay_pos_];
      delay_line_[delay_pos_] = x;
      delay_pos_ = (delay_pos_ + 1) % guard_;
    }
    const std::int64_t output_position = position_ - static_cast<std::int64_t>(guard_);
    ++position_;
    if (output_position < 0) {
      out[k] = {};
      continue;
    }
    ++seen_;
    if (output_position <= zero_until_) {
      out[k] = {};
      ++blanked_;
    } else {
      out[k] = delayed;
    }
  }
}

double PulseBlanker::blanked_fraction() const {
  return seen_ == 0 ? 0.0 : static_cast<double>(blanked_) / static_cast<double>(seen_);
}

}  // namespace deepnav
