// The jamming judge on hand-made figures: each criterion alone fails a point, at its
// threshold and not before, and the summary over the channels.
#include "tools/bench/jam_judge.hpp"

#include <gtest/gtest.h>

namespace deepnav::bench {
namespace {

JamChannels channels(std::initializer_list<double> tracked_fractions) {
  JamChannels out;
  int prn = 1;
  for (double f : tracked_fractions) out[std::to_string(prn++)] = {f, f, 45.0};
  return out;
}

/// Every GNSS fix, within a metre.
JamSolutionFigures good_solution() {
  JamSolutionFigures s;
  s.solutions = s.fixes = 16;
  s.solution_availability = s.fix_availability = 1.0;
  s.horizontal_max_m = 1.0;
  s.vertical_max_m = 1.5;
  return s;
}

TEST(JamJudge, PassesAPointThatMeetsEveryCriterion) {
  const JamVerdict v = judge_jam_point(channels({1.0, 0.9, 0.8}), good_solution());
  EXPECT_FALSE(v.failed);
  EXPECT_EQ(v.failure, "");
  EXPECT_DOUBLE_EQ(v.tracked_fraction_mean, 0.9);
  EXPECT_DOUBLE_EQ(v.tracked_fraction_min, 0.8);
  EXPECT_DOUBLE_EQ(v.signal_fraction_mean, 0.9);
  ASSERT_TRUE(v.cn0_mean_dbhz.has_value());
  EXPECT_DOUBLE_EQ(*v.cn0_mean_dbhz, 45.0);
}

TEST(JamJudge, FixAvailabilityBelowNinetyFivePercentFails) {
  JamSolutionFigures s = good_solution();
  s.fix_availability = 0.95;
  EXPECT_FALSE(judge_jam_point(channels({1.0}), s).failed);  // at the threshold: kept
  s.fix_availability = 0.94;
  const JamVerdict v = judge_jam_point(channels({1.0}), s);
  EXPECT_TRUE(v.failed);
  EXPECT_EQ(v.failure, "GNSS fixes missing");
}

TEST(JamJudge, HorizontalOrVerticalErrorOverTenMetresFails) {
  JamSolutionFigures s = good_solution();
  s.horizontal_max_m = 10.0;
  EXPECT_FALSE(judge_jam_point(channels({1.0}), s).failed);
  s.horizontal_max_m = 10.01;
  EXPECT_EQ(judge_jam_point(channels({1.0}), s).failure, "error over 10 m");
  s = good_solution();
  s.vertical_max_m = 12.0;
  EXPECT_EQ(judge_jam_point(channels({1.0}), s).failure, "error over 10 m");
}

TEST(JamJudge, NoSolutionIsNoErrorButMissingFixes) {
  JamSolutionFigures s;  // no solution at all: no error figure, no availability
  const JamVerdict v = judge_jam_point(channels({1.0}), s);
  EXPECT_EQ(v.failure, "GNSS fixes missing");
}

TEST(JamJudge, TrackedLessThanHalfTheTimeOnAverageFails) {
  EXPECT_FALSE(judge_jam_point(channels({0.5, 0.5}), good_solution()).failed);
  const JamVerdict v = judge_jam_point(channels({0.9, 0.0}), good_solution());  // mean 0.45
  EXPECT_TRUE(v.failed);
  EXPECT_EQ(v.failure, "tracking lost");
  EXPECT_DOUBLE_EQ(v.tracked_fraction_min, 0.0);
}

TEST(JamJudge, NamesEveryCriterionMissedInOrder) {
  JamSolutionFigures s = good_solution();
  s.fix_availability = 0.2;
  s.vertical_max_m = 40.0;
  const JamVerdict v = judge_jam_point(channels({0.1, 0.2}), s);
  EXPECT_TRUE(v.failed);
  EXPECT_EQ(v.failure, "GNSS fixes missing; error over 10 m; tracking lost");
}

TEST(JamJudge, OtherCriteriaMoveTheVerdict) {
  FailureCriteria strict;
  strict.max_error_m = 1.2;
  strict.min_tracked_fraction = 0.95;
  const JamVerdict v = judge_jam_point(channels({1.0, 0.8}), good_solution(), strict);
  EXPECT_EQ(v.failure, "error over 1.2 m; tracking lost");
}

TEST(JamJudge, MeanCarrierToNoiseOverTheChannelsWithAnEstimate) {
  JamChannels c = channels({1.0, 1.0, 0.0});
  c["1"].cn0_dbhz = 40.0;
  c["2"].cn0_dbhz = 44.0;
  c["3"].cn0_dbhz.reset();  // never tracked after the estimate settled
  const JamVerdict v = judge_jam_point(c, good_solution());
  ASSERT_TRUE(v.cn0_mean_dbhz.has_value());
  EXPECT_DOUBLE_EQ(*v.cn0_mean_dbhz, 42.0);
  EXPECT_DOUBLE_EQ(v.tracked_fraction_mean, 2.0 / 3.0);
}

TEST(JamJudge, WithoutChannelsNothingIsTracked) {
  const JamVerdict v = judge_jam_point({}, good_solution());
  EXPECT_EQ(v.tracked_fraction_mean, 0.0);
  EXPECT_EQ(v.tracked_fraction_min, 0.0);
  EXPECT_FALSE(v.cn0_mean_dbhz.has_value());
  EXPECT_EQ(v.failure, "tracking lost");
}

}  // namespace
}  // namespace deepnav::bench
