#include "receiver/tracking/bit_synchronizer.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav {

BitSynchronizer::BitSynchronizer(int min_bits, double z) : min_bits_(min_bits), z_(z) {}

void BitSynchronizer::reset() {
  last_period_.reset();
  partial_.fill(0.0);
  partial_ms_.fill(0);
  metric_.fill(0.0);
  bits_.fill(0);
  noise_power_ = 0.0;
  noise_count_ = 0;
}

int BitSynchronizer::bits_seen() const { return *std::min_element(bits_.begin(), bits_.end()); }

std::optional<int> BitSynchronizer::add(std::int64_t period, const std::complex<double>& prompt,
                                        const std::complex<double>& noise) {
  if (last_period_ && period != *last_period_ + 1) reset();
  last_period_ = period;
  noise_power_ += std::norm(noise);
  ++noise_count_;
  const int phase = static_cast<int>(((period % 20) + 20) % 20);
  for (int j = 0; j < 20; ++j) {
    partial_[static_cast<std::size_t>(j)] += prompt;
    ++partial_ms_[static_cast<std::size_t>(j)];
    // Candidate j has bits starting at periods = j (mod 20): this period ends one.
    if ((phase + 1) % 20 == j) {
      if (partial_ms_[static_cast<std::size_t>(j)] == 20) {
        metric_[static_cast<std::size_t>(j)] += std::abs(partial_[static_cast<std::size_t>(j)]);
        ++bits_[static_cast<std::size_t>(j)];
      }
      partial_[static_cast<std::size_t>(j)] = 0.0;
      partial_ms_[static_cast<std::size_t>(j)] = 0;
    }
  }
  const int n = bits_seen();
  if (n < min_bits_) return std::nullopt;
  std::array<double, 20> mean{};
  for (std::size_t j = 0; j < 20; ++j) mean[j] = metric_[j] / bits_[j];
  const auto best = std::max_element(mean.begin(), mean.end());
  double second = 0.0;
  for (auto it = mean.begin(); it != mean.end(); ++it)
    if (it != best) second = std::max(second, *it);
  // Per-component noise variance of one 1 ms prompt; the lead over a neighbouring candidate
  // differs by two milliseconds of noise per bit.
  const double sigma2 = noise_power_ / noise_count_ / 2.0;
  const double lead_sigma = std::sqrt(2.0 * sigma2 / n);
  if (*best - second > z_ * lead_sigma) return static_cast<int>(std::distance(mean.begin(), best));
  return std::nullopt;
}

}  // namespace deepnav
