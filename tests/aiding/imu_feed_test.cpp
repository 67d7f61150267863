// The IMU log as both aided navigators take it: samples in order, a gap reached once the
// time is well past its last sample (or as soon as a sample after it is due), the end once.
#include "aiding/imu_feed.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace deepnav::aiding {
namespace {

/// 100 Hz from 0.01 s to 1.00 s without 0.31 .. 0.49 s (a gap from 0.30 s to 0.50 s).
ImuLog log_with_gap() {
  ImuLog log;
  log.nominal_interval_s = 0.01;
  log.source = "imu.csv";
  for (int k = 1; k <= 100; ++k) {
    ImuSample s;
    s.t_s = 0.01 * k;
    if (k <= 30 || k >= 50) log.samples.push_back(s);
  }
  log.gaps.push_back({33, 0.30, 0.50});
  return log;
}

/// What one advance did: samples taken, gaps met (their start), whether the end came.
struct Advance {
  int samples = 0;
  std::vector<double> gaps;
  bool ended = false;
};

Advance advance(ImuFeed& feed, double t_s) {
  Advance a;
  feed.advance(
      t_s, [&](const ImuSample&) { ++a.samples; }, [&](const ImuGap& g) { a.gaps.push_back(g.t_before_s); },
      [&] { a.ended = true; });
  return a;
}

TEST(ImuFeed, StopsInsideAGapOnceAndCoversAgainAfterIt) {
  const ImuLog log = log_with_gap();
  ImuFeed feed(log);
  EXPECT_EQ(advance(feed, 0.30).samples, 30);
  EXPECT_TRUE(feed.covers());
  // Past the gap's start by less than 1.5 intervals: not reached yet.
  EXPECT_TRUE(advance(feed, 0.31).gaps.empty());
  const Advance in = advance(feed, 0.40);
  ASSERT_EQ(in.gaps.size(), 1u);
  EXPECT_DOUBLE_EQ(in.gaps[0], 0.30);
  EXPECT_FALSE(feed.covers());
  EXPECT_TRUE(advance(feed, 0.45).gaps.empty());  // once only
  const Advance after = advance(feed, 0.60);
  EXPECT_EQ(after.samples, 11);
  EXPECT_TRUE(after.gaps.empty());
  EXPECT_TRUE(feed.covers());
  EXPECT_DOUBLE_EQ(feed.last_sample_t_s(), 0.60);
  EXPECT_EQ(feed.describe(log.gaps[0], 0.1), "IMU data missing from t = 0.200 s to 0.400 s (imu.csv line 33)");
}

TEST(ImuFeed, AGapBetweenTwoCallsIsReachedBeforeTheSamplesAfterIt) {
  // Epochs 0.25 s apart: the gap lies between two of them; the INS must still stop there,
  // before the samples after the gap reach it.
  const ImuLog log = log_with_gap();
  ImuFeed feed(log);
  advance(feed, 0.25);
  std::vector<std::string> order;
  feed.advance(
      0.75, [&](const ImuSample& s) { order.push_back(s.t_s < 0.4 ? "before" : "after"); },
      [&](const ImuGap&) { order.push_back("gap"); }, [] {});
  ASSERT_EQ(order.size(), 5u + 1u + 26u);
  EXPECT_EQ(order[4], "before");
  EXPECT_EQ(order[5], "gap");
  EXPECT_EQ(order[6], "after");
  EXPECT_TRUE(feed.covers());
}

TEST(ImuFeed, TheEndOfTheLogIsReachedOnce) {
  const ImuLog log = log_with_gap();
  ImuFeed feed(log);
  EXPECT_FALSE(advance(feed, 1.01).ended);  // within 1.5 intervals of the last sample
  EXPECT_TRUE(advance(feed, 1.25).ended);
  EXPECT_FALSE(feed.covers());
  EXPECT_TRUE(feed.ended());
  EXPECT_FALSE(advance(feed, 1.5).ended);
}

}  // namespace
}  // namespace deepnav::aiding
