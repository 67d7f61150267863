// The coupling benchmark's scoring on hand-made epochs and runs.
#include "tools/bench/coupling_scoring.hpp"

#include <gtest/gtest.h>

namespace deepnav::bench {
namespace {

/// An epoch as a coupling point records it: t, mode, valid, north, east, down, velocity error.
nlohmann::json epoch(double t, const std::string& mode, bool valid, double n, double e, double d) {
  return {t, mode, valid, n, e, d, 0.1};
}

TEST(CouplingScoreRun, RmsOverValidEpochsFromTheStartOfScoring) {
  const nlohmann::json epochs = {epoch(10.0, "ultra", true, 100.0, 0.0, 0.0),  // before scoring: ignored
                                 epoch(30.0, "ultra", true, 3.0, 4.0, 0.0), epoch(31.0, "coast", true, 0.0, 0.0, 12.0),
                                 epoch(32.0, "ultra", false, 50.0, 50.0, 50.0)};  // no solution: time only
  const RunScore s = score_run(epochs, "ultra", 30.0, 31.0);
  EXPECT_DOUBLE_EQ(s.rms_h_m, std::sqrt(25.0 / 2.0));
  EXPECT_DOUBLE_EQ(s.rms_3d_m, std::sqrt((25.0 + 144.0) / 2.0));
  ASSERT_TRUE(s.error_at_m.has_value());
  EXPECT_EQ(*s.error_at_m, Eigen::Vector3d(0.0, 0.0, 12.0));
  EXPECT_EQ(s.scored_s, 3.0);
  EXPECT_EQ(s.in_mode_s, 2.0);
}

TEST(CouplingScoreRun, NoValidEpochNoFigures) {
  const RunScore s = score_run(nlohmann::json::array({epoch(40.0, "loose", false, 0, 0, 0)}), "loose", 30.0, 150.0);
  EXPECT_TRUE(std::isnan(s.rms_h_m));
  EXPECT_FALSE(s.error_at_m.has_value());
}

TEST(CouplingScoreRun, HeightSettledAfterAMismatchFromTheFirstDetection) {
  const nlohmann::json epochs = {epoch(30.0, "tight", true, 0.0, 0.0, 7.0), epoch(40.0, "tight", true, 9.0, 9.0, 3.0),
                                 epoch(41.0, "tight", false, 0.0, 0.0, 99.0),  // no solution: left out
                                 epoch(42.0, "tight", true, 0.0, 0.0, -4.0)};
  EXPECT_DOUBLE_EQ(vertical_rms_from(epochs, 40.0), std::sqrt((9.0 + 16.0) / 2.0));
  EXPECT_TRUE(std::isnan(vertical_rms_from(epochs, 50.0)));

  EXPECT_FALSE(mismatch_found_s({{"troposphere_mismatch_s", nullptr}, {"ionosphere_mismatch_s", nullptr}}));
  EXPECT_FALSE(mismatch_found_s(nlohmann::json::object())) << "points made before the watches recorded nothing";
  EXPECT_EQ(mismatch_found_s({{"troposphere_mismatch_s", 32.0}, {"ionosphere_mismatch_s", nullptr}}), 32.0);
  EXPECT_EQ(mismatch_found_s({{"troposphere_mismatch_s", 32.0}, {"ionosphere_mismatch_s", 26.0}}), 26.0);
}

TEST(CouplingSpread, MeanAndSampleStandardDeviation) {
  const Spread s = spread({1.0, 2.0, 3.0});
  EXPECT_EQ(s.n, 3);
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.std, 1.0);
  EXPECT_EQ(spread({5.0}).std, 0.0);
  EXPECT_TRUE(std::isnan(spread({}).mean));
}

TEST(CouplingPairedVerdict, TwoStandardErrorsDecide) {
  EXPECT_EQ(paired_verdict({1.0, 1.1, 0.9}, {2.0, 2.1, 1.9}), "yes");
  EXPECT_EQ(paired_verdict({2.0, 2.1, 1.9}, {1.0, 1.1, 0.9}), "no");
  EXPECT_EQ(paired_verdict({1.0, 2.0, 1.0}, {2.0, 1.0, 1.1}), "tie");
  EXPECT_EQ(paired_verdict({1.0}, {2.0}), "yes(1 run)");
  EXPECT_EQ(paired_verdict({3.0}, {2.0}), "no(1 run)");
  EXPECT_EQ(paired_verdict({}, {}), "n/a");
}

}  // namespace
}  // namespace deepnav::bench
