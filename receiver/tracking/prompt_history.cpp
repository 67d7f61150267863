#include "receiver/tracking/prompt_history.hpp"

#include <cmath>

namespace deepnav {
namespace {

constexpr int kPeriodsPerBit = 20;
/// Weight of the reference phase against each new bit in the decision feedback: about five
/// bits (0.1 s) of memory, long enough to average the noise of one bit at 30 dB-Hz, short
/// enough to follow the phase of a carrier loop still pulling in.
constexpr double kReferenceMemory = 0.8;

}  // namespace

PromptHistory::PromptHistory(std::size_t max_periods) : max_periods_(max_periods) {}

void PromptHistory::add(std::int64_t period, const std::complex<double>& prompt, std::int64_t first_sample) {
  if (!prompts_.empty() && period != prompts_.back().period + 1) prompts_.clear();
  prompts_.push_back(Prompt{period, prompt, first_sample});
  while (prompts_.size() > max_periods_) prompts_.pop_front();
}

PromptHistory::Bits PromptHistory::bits(std::int64_t bit_edge_period) const {
  Bits out;
  // Complex sums of the whole bits, oldest first; the prompts after the last edge are the tail.
  std::vector<std::complex<double>> sums;
  std::size_t i = 0;
  while (i < prompts_.size() && code_periods_into_bit(prompts_[i].period, bit_edge_period) != 0) ++i;
  for (; i + kPeriodsPerBit <= prompts_.size(); i += kPeriodsPerBit) {
    std::complex<double> sum{};
    for (int k = 0; k < kPeriodsPerBit; ++k) sum += prompts_[i + static_cast<std::size_t>(k)].value;
    sums.push_back(sum);
    out.whole.push_back(PromptBit{0.0, prompts_[i].first_sample, prompts_[i].period});
  }
  if (i < prompts_.size()) {
    out.tail.first_sample = prompts_[i].first_sample;
    out.tail.code_period = prompts_[i].period;
    for (; i < prompts_.size(); ++i) {
      out.tail.soft += prompts_[i].value.real();
      ++out.tail.periods;
    }
  }
  if (sums.empty()) return out;
  // Backwards from the newest bit, whose phase the locked loop holds on the real axis.
  double mean_magnitude = 0.0;
  for (const auto& s : sums) mean_magnitude += std::abs(s);
  std::complex<double> reference{mean_magnitude / static_cast<double>(sums.size()), 0.0};
  for (std::size_t k = sums.size(); k-- > 0;) {
    const double r = std::abs(reference);
    const std::complex<double> unit = r > 0.0 ? reference / r : std::complex<double>{1.0, 0.0};
    const double soft = (sums[k] * std::conj(unit)).real();
    out.whole[k].soft = soft;
    const double sign = soft < 0.0 ? -1.0 : 1.0;
    reference = kReferenceMemory * reference + (1.0 - kReferenceMemory) * sign * sums[k];
  }
  return out;
}

}  // namespace deepnav
