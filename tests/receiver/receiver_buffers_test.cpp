// The receiver's small bookkeeping buffers: windowed sums (lock detectors) and the sample
// history kept for re-acquisition.
#include <gtest/gtest.h>

#include <numeric>
#include <random>
#include <vector>

#include "receiver/sources/sample_history.hpp"
#include "receiver/tracking/windowed_sum.hpp"

namespace deepnav {
namespace {

TEST(WindowedSum, MatchesAFreshSumOverTheLastValuesWhateverTheCapacityDoes) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> value(0.0, 1e6);
  WindowedSum w;
  std::vector<double> all;
  std::size_t capacity = 200;
  for (int k = 0; k < 30000; ++k) {
    if (k == 12000) capacity = 20;    // shrinking drops the oldest at the next push
    if (k == 20000) capacity = 2000;  // growing keeps everything until full
    const double v = value(rng);
    all.push_back(v);
    w.push(v, capacity);
    const std::size_t held = std::min<std::size_t>(w.size(), all.size());
    const double exact = std::accumulate(all.end() - static_cast<std::ptrdiff_t>(held), all.end(), 0.0);
    ASSERT_NEAR(w.sum(), exact, 1e-9 * exact) << k;
    ASSERT_LE(w.size(), capacity);
  }
  EXPECT_EQ(w.size(), 2000u);
  EXPECT_NEAR(w.mean(), w.sum() / 2000.0, 1e-9);
  w.clear();
  EXPECT_TRUE(w.empty());
  EXPECT_EQ(w.sum(), 0.0);
  EXPECT_EQ(w.mean(), 0.0);
}

TEST(SampleHistory, HoldsTheLastSamplesInOrderAcrossWrapsAndOversizedBlocks) {
  const std::size_t cap = 1000;
  SampleHistory h(cap);
  std::vector<Sample> stream;
  std::int64_t index = 0;
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> len(1, 1700);  // some blocks longer than the history
  for (int b = 0; b < 200; ++b) {
    const auto n = static_cast<std::size_t>(len(rng));
    std::vector<Sample> block(n);
    for (std::size_t k = 0; k < n; ++k)
      block[k] = {static_cast<std::int16_t>((index + static_cast<std::int64_t>(k)) % 30000),
                  static_cast<std::int16_t>(b)};
    h.append(block.data(), n, index);
    stream.insert(stream.end(), block.begin(), block.end());
    index += static_cast<std::int64_t>(n);
    const std::size_t held = std::min(cap, stream.size());
    ASSERT_EQ(h.size(), held);
    ASSERT_EQ(h.full(), held == cap);
    ASSERT_EQ(h.first_index(), index - static_cast<std::int64_t>(held));
    const auto got = h.in_order();
    ASSERT_TRUE(std::equal(got.begin(), got.end(), stream.end() - static_cast<std::ptrdiff_t>(held))) << b;
  }
  h.clear();
  EXPECT_EQ(h.size(), 0u);
  EXPECT_FALSE(h.full());
  h.append(stream.data(), 10, 5);
  EXPECT_EQ(h.first_index(), 5);
  EXPECT_EQ(h.in_order().size(), 10u);
}

}  // namespace
}  // namespace deepnav
