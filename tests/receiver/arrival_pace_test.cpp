// The pace of a stream told from arrival times: unknown until four half-second segments
// exist, the median segment rate (so a stall and its burst, or a hole, do not sway it), a
// trickle's pace known from its last few pieces however far apart, and forgotten on
// restart() while the whole-stream figure stays.
#include "receiver/stream/arrival_pace.hpp"

#include <gtest/gtest.h>

namespace deepnav {
namespace {

constexpr double kFs = 1000.0;

TEST(ArrivalPace, UnknownUntilFourSegments) {
  ArrivalPace pace(kFs);
  double t = 0.0;
  pace.arrived(t, 10);
  EXPECT_FALSE(pace.median().has_value());
  EXPECT_FALSE(pace.overall().has_value());
  // 10 samples every 10 ms: real time; four 0.5 s segments take 2 s of arrivals.
  for (int i = 0; i < 150; ++i) pace.arrived(t += 0.01, 10);
  EXPECT_FALSE(pace.median().has_value());
  for (int i = 0; i < 60; ++i) pace.arrived(t += 0.01, 10);
  ASSERT_TRUE(pace.median().has_value());
  EXPECT_NEAR(*pace.median(), 1.0, 1e-9);
  EXPECT_NEAR(*pace.mean(), 1.0, 1e-9);
  EXPECT_NEAR(*pace.overall(), 1.0, 1e-9);
}

TEST(ArrivalPace, AStallAndItsBurstDoNotSwayTheMedian) {
  ArrivalPace pace(kFs);
  double t = 0.0;
  for (int i = 0; i < 200; ++i) pace.arrived(t += 0.01, 10);
  t += 0.4;  // nothing for 0.4 s, then the samples of that time at once
  pace.arrived(t, 400);
  for (int i = 0; i < 150; ++i) pace.arrived(t += 0.01, 10);
  EXPECT_NEAR(*pace.median(), 1.0, 1e-9);
}

TEST(ArrivalPace, HalfRealTimeAndATrickle) {
  ArrivalPace half(kFs);
  double t = 0.0;
  for (int i = 0; i < 400; ++i) half.arrived(t += 0.02, 10);
  EXPECT_NEAR(*half.median(), 0.5, 1e-9);
  EXPECT_NEAR(*half.overall(), 0.5, 1e-9);
  // One sample every 0.5 s (1/500 of the rate): pieces farther apart than a segment, and
  // the window keeps enough of them for the pace to be known after five.
  ArrivalPace trickle(kFs);
  t = 0.0;
  for (int i = 0; i < 4; ++i) trickle.arrived(t += 0.5, 1);
  EXPECT_FALSE(trickle.median().has_value());
  trickle.arrived(t += 0.5, 1);
  ASSERT_TRUE(trickle.median().has_value());
  EXPECT_NEAR(*trickle.median(), 0.002, 1e-12);
  for (int i = 0; i < 20; ++i) trickle.arrived(t += 0.5, 1);
  EXPECT_NEAR(*trickle.mean(), 0.002, 1e-12);
}

TEST(ArrivalPace, RestartForgetsTheWindowNotTheStream) {
  ArrivalPace pace(kFs);
  double t = 0.0;
  for (int i = 0; i < 300; ++i) pace.arrived(t += 0.01, 10);
  ASSERT_TRUE(pace.median().has_value());
  pace.restart();
  EXPECT_FALSE(pace.median().has_value());
  EXPECT_FALSE(pace.mean().has_value());
  for (int i = 0; i < 300; ++i) pace.arrived(t += 0.01, 5);
  EXPECT_NEAR(*pace.median(), 0.5, 1e-9);
  EXPECT_NEAR(*pace.overall(), 0.75, 0.01);
}

}  // namespace
}  // namespace deepnav
