#include "receiver/tracking/prompt_history.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace deepnav {
namespace {

/// 1 ms prompts of data bits (edge at period 7) whose carrier phase drifts at `residual_hz`
/// and ends at phase 0 (where a locked loop holds it), with noise.
PromptHistory prompts(const std::vector<int>& bits, double residual_hz, std::int64_t first_period, std::uint64_t seed) {
  PromptHistory h(100000);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto n = static_cast<std::int64_t>(bits.size()) * 20;
  for (std::int64_t p = first_period; p < 7 + n; ++p) {
    const double phase = 2.0 * std::numbers::pi * residual_hz * static_cast<double>(p - (7 + n)) * 1e-3;
    const double sign = bits[static_cast<std::size_t>((p - 7) / 20)] ? -1.0 : 1.0;
    h.add(p, std::polar(2.0 * sign, phase) + std::complex<double>{noise(rng), noise(rng)}, 1000 * p);
  }
  return h;
}

TEST(PromptHistory, BitsFollowTheDriftingPhaseBackFromTheLockedEnd) {
  std::vector<int> bits;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 100; ++k) bits.push_back(static_cast<int>(rng() & 1u));
  // 0.4 Hz of residual frequency turns the phase by 0.8 cycles over the 2 s kept.
  const PromptHistory h = prompts(bits, 0.4, 0, 4);
  const PromptHistory::Bits b = h.bits(7);
  ASSERT_EQ(b.whole.size(), bits.size());
  for (std::size_t k = 0; k < bits.size(); ++k) {
    EXPECT_EQ(b.whole[k].soft < 0.0, bits[k] != 0) << "bit " << k;
    EXPECT_EQ(b.whole[k].code_period, 7 + 20 * static_cast<std::int64_t>(k));
    EXPECT_EQ(b.whole[k].first_sample, 1000 * b.whole[k].code_period);
  }
  EXPECT_EQ(b.tail.periods, 0);
}

TEST(PromptHistory, APartialFirstBitIsSkippedAndTheBitUnderWayIsTheTail) {
  const std::vector<int> bits(10, 0);
  PromptHistory h = prompts(bits, 0.0, 12, 5);  // starts 5 periods into the first bit
  for (std::int64_t p = 207; p < 213; ++p) h.add(p, {2.0, 0.0}, 1000 * p);
  const PromptHistory::Bits b = h.bits(7);
  EXPECT_EQ(b.whole.size(), bits.size() - 1);
  EXPECT_EQ(b.whole.front().code_period, 27);
  EXPECT_EQ(b.tail.periods, 6);
  EXPECT_EQ(b.tail.code_period, 207);
  EXPECT_NEAR(b.tail.soft, 12.0, 1e-12);
}

TEST(PromptHistory, AGapInThePeriodsStartsOver) {
  PromptHistory h(1000);
  for (std::int64_t p = 0; p < 40; ++p) h.add(p, {1.0, 0.0}, p);
  for (std::int64_t p = 45; p < 85; ++p) h.add(p, {1.0, 0.0}, p);
  EXPECT_EQ(h.size(), 40u);
  EXPECT_EQ(h.bits(5).whole.size(), 2u);  // 45-64 and 65-84
}

}  // namespace
}  // namespace deepnav
