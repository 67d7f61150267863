#include "receiver/tracking/e1_secondary_sync.hpp"

#include <stdexcept>

#include "signals/galileo/e1_codes.hpp"

namespace deepnav {
namespace {

constexpr int kLength = galileo::kE1cSecondaryLength_chips;
constexpr double kMinAlignment = 0.5;

}  // namespace

int secondary_chip(std::int64_t period, int offset) {
  const auto index = static_cast<std::size_t>(((period + offset) % kLength + kLength) % kLength);
  return galileo::e1c_secondary_chips()[index];
}

SecondaryCodeSynchronizer::SecondaryCodeSynchronizer(int window_periods, double margin)
    : window_(window_periods), margin_(margin) {
  if (window_periods < kLength + 1)
    throw std::invalid_argument("E1 secondary sync: the window needs at least 26 prompts (25 products)");
  if (!(margin > 1.0)) throw std::invalid_argument("E1 secondary sync: the margin must exceed 1");
}

std::optional<SecondaryCodePhase> SecondaryCodeSynchronizer::add(std::int64_t period,
                                                                 const std::complex<double>& prompt) {
  if (!prompts_.empty() && period != last_period_ + 1) prompts_.clear();
  last_period_ = period;
  prompts_.push_back(prompt);
  if (static_cast<int>(prompts_.size()) > window_) prompts_.pop_front();
  if (static_cast<int>(prompts_.size()) < window_) return std::nullopt;

  const std::int64_t first = period - window_ + 1;  // period of prompts_[0]
  double best = 0.0, second = 0.0, magnitude = 0.0;
  int best_offset = -1;
  for (int k = 1; k < window_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    magnitude += std::abs(prompts_[i] * std::conj(prompts_[i - 1]));
  }
  for (int offset = 0; offset < kLength; ++offset) {
    std::complex<double> sum;
    for (int k = 1; k < window_; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const double chips = secondary_chip(first + k, offset) * secondary_chip(first + k - 1, offset);
      sum += prompts_[i] * std::conj(prompts_[i - 1]) * chips;
    }
    const double score = sum.real();
    if (score > best) {
      second = best;
      best = score;
      best_offset = offset;
    } else if (score > second) {
      second = score;
    }
  }
  // The runner-up well behind, and the products mostly aligned with the best phase (noise alone
  // gets about a quarter of their magnitude sum, a 35 dB-Hz pilot over 0.8 of it).
  if (best_offset < 0 || best < margin_ * second || best < kMinAlignment * magnitude) return std::nullopt;
  // Which side of the Costas ambiguity: the wiped prompts, rotated onto the first one's phase.
  std::complex<double> coherent;
  for (int k = 0; k < window_; ++k)
    coherent += prompts_[static_cast<std::size_t>(k)] * static_cast<double>(secondary_chip(first + k, best_offset));
  return SecondaryCodePhase{best_offset, coherent.real() < 0.0 ? -1 : 1};
}

}  // namespace deepnav
