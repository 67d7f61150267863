#include "signals/sim/bandlimited_noise.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav {
namespace {

constexpr double kKaiserBeta = 5.65;             // 0.1102 (A - 8.7) for A = 60 dB
constexpr double kTransitionOfBandwidth = 0.25;  // transition band width / B
constexpr float kSqrtHalf = 0.70710678118654752f;

}  // namespace

std::vector<float> design_noise_shaping_taps(double bandwidth_hz, double sample_rate_hz) {
  if (bandwidth_hz >= sample_rate_hz) return {1.0f};
  const double transition = kTransitionOfBandwidth * bandwidth_hz / sample_rate_hz;  // cycles/sample
  int n = static_cast<int>(std::ceil((60.0 - 8.0) / (2.285 * 2.0 * M_PI * transition)));
  n = std::clamp(n | 1, 3, BandLimitedNoise::kMaxTaps);
  const double cutoff = 0.5 * bandwidth_hz / sample_rate_hz;  // cycles/sample
  const double half = 0.5 * (n - 1);
  const double i0_beta = std::cyl_bessel_i(0.0, kKaiserBeta);
  std::vector<double> h(static_cast<std::size_t>(n));
  double energy = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = k - half;
    const double sinc = t == 0.0 ? 2.0 * cutoff : std::sin(2.0 * M_PI * cutoff * t) / (M_PI * t);
    const double r = t / half;
    const double window = std::cyl_bessel_i(0.0, kKaiserBeta * std::sqrt(std::max(0.0, 1.0 - r * r))) / i0_beta;
    h[static_cast<std::size_t>(k)] = sinc * window;
    energy += sinc * window * sinc * window;
  }
  std::vector<float> taps(h.size());
  const double scale = 1.0 / std::sqrt(energy);
  for (std::size_t k = 0; k < h.size(); ++k) taps[k] = static_cast<float>(h[k] * scale);
  return taps;
}

BandLimitedNoise::BandLimitedNoise(double bandwidth_hz, double sample_rate_hz, std::uint64_t seed)
    : taps_(design_noise_shaping_taps(bandwidth_hz, sample_rate_hz)),
      noise_i_(splitmix64(seed ^ 0x49ULL)),
      noise_q_(splitmix64(seed ^ 0x51ULL)) {}

// y[n] = sum_k h[k] x[n + N-1 - k]: the tap loop is outside so the inner loop runs over
// consecutive outputs (vectorises); tiles keep the accumulators in L1. The summation order
// per output is fixed, so results do not depend on block boundaries.
void BandLimitedNoise::filter(float* y, const float* x, std::int64_t n) const {
  constexpr std::int64_t kTile = 256;
  const int taps = static_cast<int>(taps_.size());
  for (std::int64_t t0 = 0; t0 < n; t0 += kTile) {
    const std::int64_t len = std::min(kTile, n - t0);
    float acc[kTile] = {};
    for (int k = 0; k < taps; ++k) {
      const float h = taps_[static_cast<std::size_t>(k)];
      const float* xs = x + t0 + (taps - 1 - k);
      for (std::int64_t j = 0; j < len; ++j) acc[j] += h * xs[j];
    }
    std::copy(acc, acc + len, y + t0);
  }
}

void BandLimitedNoise::generate(std::span<std::complex<float>> out, std::int64_t first_sample, float amplitude) {
  const std::int64_t n = static_cast<std::int64_t>(out.size());
  if (n == 0) return;
  const std::int64_t hist = taps() - 1;
  const auto total = static_cast<std::size_t>(hist + n);
  if (history_valid_ && next_sample_ == first_sample && raw_i_.size() >= static_cast<std::size_t>(hist)) {
    // Keep the last taps-1 raw samples of the previous block as history.
    std::copy(raw_i_.end() - hist, raw_i_.end(), raw_i_.begin());
    std::copy(raw_q_.end() - hist, raw_q_.end(), raw_q_.begin());
    raw_i_.resize(total);
    raw_q_.resize(total);
  } else {
    raw_i_.resize(total);
    raw_q_.resize(total);
    noise_i_.fill_real(std::span<float>(raw_i_.data(), static_cast<std::size_t>(hist)), first_sample - hist, kSqrtHalf);
    noise_q_.fill_real(std::span<float>(raw_q_.data(), static_cast<std::size_t>(hist)), first_sample - hist, kSqrtHalf);
  }
  noise_i_.fill_real(std::span<float>(raw_i_.data() + hist, static_cast<std::size_t>(n)), first_sample, kSqrtHalf);
  noise_q_.fill_real(std::span<float>(raw_q_.data() + hist, static_cast<std::size_t>(n)), first_sample, kSqrtHalf);
  history_valid_ = true;
  next_sample_ = first_sample + n;

  out_i_.resize(static_cast<std::size_t>(n));
  out_q_.resize(static_cast<std::size_t>(n));
  filter(out_i_.data(), raw_i_.data(), n);
  filter(out_q_.data(), raw_q_.data(), n);
  for (std::int64_t k = 0; k < n; ++k)
    out[static_cast<std::size_t>(k)] = {amplitude * out_i_[static_cast<std::size_t>(k)],
                                        amplitude * out_q_[static_cast<std::size_t>(k)]};
}

}  // namespace deepnav
