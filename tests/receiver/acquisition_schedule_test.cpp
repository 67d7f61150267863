// When the receiver's FFT acquisition runs: a window of one search's samples kept while a
// channel is free, a re-acquisition every interval once the window is full, the window
// restarted after a gap, the PRNs the configuration allows, and no search on too few samples.
#include "receiver/acquisition/acquisition_schedule.hpp"

#include <gtest/gtest.h>

namespace deepnav {
namespace {

constexpr double kFs = 2.046e6;
constexpr std::int64_t kBlock = 20460;  // 10 ms

AcquisitionConfig config() {
  AcquisitionConfig c;
  c.sample_rate_hz = kFs;
  c.coherent_ms = 1;
  c.noncoherent = 10;
  return c;
}

SampleBlock block_at(std::int64_t first, std::int64_t n = kBlock) {
  SampleBlock b;
  b.first_sample_index = first;
  b.samples.assign(static_cast<std::size_t>(n), Sample(3, -2));
  return b;
}

TEST(AcquisitionSchedule, TheWindowIsOneSearchOfSamples) {
  const AcquisitionSchedule schedule(config(), 5.0);
  EXPECT_EQ(schedule.window_samples(), 20460u);  // 10 x 1 ms at 2.046 Msps
}

TEST(AcquisitionSchedule, ReacquiresEveryIntervalOnceTheWindowIsFullAndAChannelFree) {
  AcquisitionSchedule schedule(config(), 5.0);
  schedule.keep(block_at(0, 10000), true);
  EXPECT_FALSE(schedule.reacquisition_due(5.0, true));  // the window is not full yet
  schedule.keep(block_at(10000, 10460), true);
  ASSERT_TRUE(schedule.window().full());
  EXPECT_EQ(schedule.window().first_index(), 0);
  EXPECT_FALSE(schedule.reacquisition_due(5.0, false));  // no channel free
  EXPECT_TRUE(schedule.reacquisition_due(5.0, true));
  EXPECT_FALSE(schedule.reacquisition_due(9.9, true));
  EXPECT_TRUE(schedule.reacquisition_due(10.0, true));
  // The window holds the latest samples.
  schedule.keep(block_at(20460), true);
  EXPECT_EQ(schedule.window().first_index(), 20460);
}

TEST(AcquisitionSchedule, TheWindowEmptiesWhileNoChannelIsFreeAndAfterAGap) {
  AcquisitionSchedule schedule(config(), 5.0);
  schedule.keep(block_at(0), true);
  schedule.keep(block_at(kBlock), false);
  EXPECT_EQ(schedule.window().size(), 0u);
  schedule.keep(block_at(2 * kBlock), true);
  ASSERT_TRUE(schedule.window().full());
  schedule.restart_window();
  EXPECT_EQ(schedule.window().size(), 0u);
  EXPECT_FALSE(schedule.reacquisition_due(100.0, true));
}

TEST(AcquisitionSchedule, SearchWhenFullSkipsTheRestOfTheInterval) {
  AcquisitionSchedule schedule(config(), 5.0);
  schedule.keep(block_at(0), true);
  ASSERT_TRUE(schedule.reacquisition_due(5.0, true));
  EXPECT_FALSE(schedule.reacquisition_due(6.0, true));
  schedule.search_when_full();
  EXPECT_TRUE(schedule.reacquisition_due(6.0, true));
}

TEST(AcquisitionSchedule, SearchesOnlyThePrnsConfigured) {
  AcquisitionConfig some = config();
  some.prns = {3, 17};
  const AcquisitionSchedule limited(some, 5.0);
  EXPECT_TRUE(limited.searchable(17));
  EXPECT_FALSE(limited.searchable(4));
  const AcquisitionSchedule all(config(), 5.0);
  for (int prn = 1; prn <= 32; ++prn) EXPECT_TRUE(all.searchable(prn));
}

TEST(AcquisitionSchedule, TooFewSamplesForOneCoherentBlockAreNotSearched) {
  AcquisitionSchedule schedule(config(), 5.0);
  EXPECT_TRUE(schedule.search(std::vector<Sample>(1000, Sample(3, -2)), {1, 2, 3}).empty());
}

}  // namespace
}  // namespace deepnav
