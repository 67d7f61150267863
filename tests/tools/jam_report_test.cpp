// The jamming report's thresholds from hand-made point figures: the first failing J/S per
// seed and its median, what a mitigation gains over none on the same seeds, the J/S at
// which the signal is lost, and the files written from them.
#include "tools/bench/jam_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "tests/tools/deepnav_cli.hpp"

namespace deepnav::bench {
namespace {

struct PointFigures {
  std::string mode = "scalar", mitigation = "none";
  std::uint64_t seed = 1;
  double js_db = 20.0;
  std::string failure;  ///< "": passed
  double signal_fraction_mean = 1.0;
};

/// A point.json as run_jam_point writes it, with the figures the report reads.
nlohmann::json point(const PointFigures& f) {
  const bool failed = !f.failure.empty();
  return {{"scenario", "static"},
          {"jammer", "cw"},
          {"js_db", f.js_db},
          {"mode", f.mode},
          {"mitigation", f.mitigation},
          {"seed", f.seed},
          {"adc_bits", 2},
          {"tracked_fraction_mean", failed ? 0.3 : 0.98},
          {"tracked_fraction_min", failed ? 0.1 : 0.95},
          {"signal_fraction_mean", f.signal_fraction_mean},
          {"cn0_mean_dbhz", failed ? nlohmann::json(nullptr) : nlohmann::json(44.5)},
          {"failed", failed},
          {"failure", f.failure},
          {"channels", {{"1", {{"tracked_fraction", 0.98}, {"signal_fraction", 1.0}, {"cn0_dbhz", 44.5}}}}},
          {"solution",
           {{"solutions", 16},
            {"fixes", 16},
            {"solution_availability", 1.0},
            {"fix_availability", failed ? 0.5 : 1.0},
            {"epochs_in_mode", {{"scalar", 16.0}}},
            {"horizontal_rms_m", 1.25},
            {"horizontal_max_m", 2.5},
            {"vertical_rms_m", 2.0},
            {"vertical_max_m", 4.0}}},
          {"wall_s", 3.0}};
}

/// One series over J/S 20, 30, 40: `fails_from` per seed (0: never fails).
std::vector<nlohmann::json> series(const std::string& mode, const std::string& mitigation,
                                   const std::vector<std::pair<std::uint64_t, double>>& fails_from,
                                   const std::string& failure = "GNSS fixes missing") {
  std::vector<nlohmann::json> out;
  for (const auto& [seed, from] : fails_from)
    for (double js : {20.0, 30.0, 40.0})
      out.push_back(point({mode, mitigation, seed, js, from > 0.0 && js >= from ? failure : "", 1.0}));
  return out;
}

std::vector<nlohmann::json> join(std::vector<std::vector<nlohmann::json>> parts) {
  std::vector<nlohmann::json> out;
  for (auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

const JamThreshold& find(const std::vector<JamThreshold>& all, const std::string& mode, const std::string& mitigation) {
  for (const auto& t : all)
    if (t.mode == mode && t.mitigation == mitigation) return t;
  throw std::logic_error("no series " + mode + "/" + mitigation);
}

TEST(JamThresholds, FirstFailingJsPerSeedAndItsMedian) {
  const auto all = jam_thresholds(series("scalar", "none", {{1, 30.0}, {2, 40.0}}));
  ASSERT_EQ(all.size(), 1u);
  const JamThreshold& t = all[0];
  EXPECT_EQ(t.scenario, "static");
  EXPECT_EQ(t.jammer, "cw");
  EXPECT_EQ(t.js_min_db, 20.0);
  EXPECT_EQ(t.js_max_db, 40.0);
  EXPECT_EQ(t.first_failure_db, (std::vector<double>{30.0, 40.0}));
  EXPECT_EQ(t.median_first_failure_db, 35.0);
  EXPECT_EQ(t.failure, "GNSS fixes missing");
  EXPECT_EQ(t.gain_over_none, "");  // none itself
}

TEST(JamThresholds, AFailureAfterAPassDoesNotMoveTheThreshold) {
  // Seed 1 fails at 30, passes at 40 again: the first failure counts.
  const auto points = std::vector<nlohmann::json>{point({"scalar", "none", 1, 20.0, "", 1.0}),
                                                  point({"scalar", "none", 1, 30.0, "tracking lost", 1.0}),
                                                  point({"scalar", "none", 1, 40.0, "", 1.0})};
  const JamThreshold t = jam_thresholds(points).at(0);
  EXPECT_EQ(t.first_failure_db, std::vector<double>{30.0});
  EXPECT_EQ(t.failure, "tracking lost");
}

TEST(JamThresholds, ASeriesThatNeverFailsIsAboveTheHighestJs) {
  const JamThreshold t = jam_thresholds(series("scalar", "none", {{1, 0.0}})).at(0);
  EXPECT_TRUE(std::isinf(t.median_first_failure_db));
  EXPECT_EQ(threshold_text(t.median_first_failure_db, t.js_max_db), "> 40.0");
  EXPECT_EQ(threshold_text(35.0, t.js_max_db), "35.0");
  EXPECT_EQ(t.failure, "");
}

TEST(JamThresholds, GainOverNoneOnTheSameSeeds) {
  const auto all = jam_thresholds(
      join({series("scalar", "excision", {{1, 40.0}, {2, 40.0}}), series("scalar", "none", {{1, 30.0}, {2, 40.0}})}));
  EXPECT_EQ(find(all, "scalar", "excision").gain_over_none, "5.0");  // 40 - median(30, 40)
}

TEST(JamThresholds, GainOfAMitigationThatNeverFailedIsALowerBound) {
  const auto all =
      jam_thresholds(join({series("scalar", "excision", {{1, 0.0}}), series("scalar", "none", {{1, 20.0}})}));
  EXPECT_EQ(find(all, "scalar", "excision").gain_over_none, "> 20.0");  // 40 - 20
}

TEST(JamThresholds, GainCannotBeSaidWithoutACommonFailingBaseline) {
  auto all = jam_thresholds(join({series("scalar", "notch", {{1, 30.0}}), series("scalar", "none", {{1, 0.0}})}));
  EXPECT_EQ(find(all, "scalar", "notch").gain_over_none, "n/a (none never failed)");
  all = jam_thresholds(join({series("scalar", "notch", {{3, 30.0}}), series("scalar", "none", {{1, 20.0}})}));
  EXPECT_EQ(find(all, "scalar", "notch").gain_over_none, "n/a (no common seed)");
  // Without a series without mitigation there is nothing to compare with.
  all = jam_thresholds(series("scalar", "notch", {{1, 30.0}}));
  EXPECT_EQ(find(all, "scalar", "notch").gain_over_none, "");
}

TEST(JamThresholds, GainIsPerMode) {
  const auto all =
      jam_thresholds(join({series("scalar", "excision", {{1, 40.0}}), series("scalar", "none", {{1, 30.0}}),
                           series("ultra", "excision", {{1, 0.0}})}));
  EXPECT_EQ(all.size(), 3u);
  EXPECT_EQ(find(all, "scalar", "excision").gain_over_none, "10.0");
  EXPECT_EQ(find(all, "ultra", "excision").gain_over_none, "");  // no ultra series without mitigation
}

TEST(JamThresholds, FailureReasonsAreNamedOnce) {
  const auto points = join({series("scalar", "none", {{1, 30.0}, {2, 30.0}}, "error over 10 m"),
                            series("scalar", "none", {{3, 40.0}}, "tracking lost")});
  EXPECT_EQ(jam_thresholds(points).at(0).failure, "error over 10 m; tracking lost");
}

TEST(JamThresholds, SignalLostWhereTheSatellitesAreSeenLessThanHalfTheTime) {
  std::vector<nlohmann::json> points;
  for (double js : {20.0, 30.0, 40.0}) points.push_back(point({"scalar", "none", 1, js, "", js >= 30.0 ? 0.49 : 0.5}));
  EXPECT_EQ(jam_thresholds(points).at(0).median_signal_lost_db, 30.0);
  points.clear();
  for (double js : {20.0, 30.0, 40.0}) points.push_back(point({"scalar", "none", 1, js, "", 0.5}));
  EXPECT_TRUE(std::isinf(jam_thresholds(points).at(0).median_signal_lost_db));
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(JamReport, WritesTheThresholdsAndOneCsvRowPerPoint) {
  const test::ScratchDir dir("jam_report_test");
  const auto points =
      join({series("scalar", "excision", {{1, 40.0}, {2, 0.0}}), series("scalar", "none", {{1, 30.0}, {2, 40.0}})});
  const BenchReport report = write_jam_report(points, dir.path().string());
  const std::string md = read_file(dir / "thresholds.md");
  EXPECT_NE(
      md.find("| static | cw | scalar | none | 20..40 | 2 | 35.0 | 30.0 40.0 |  | GNSS fixes missing | > 40.0 |\n"),
      std::string::npos)
      << md;
  // Excision: seed 1 fails at 40, seed 2 never; median of (40, > 40) is above 40.
  EXPECT_NE(
      md.find("| static | cw | scalar | excision | 20..40 | 2 | > 40.0 | 40.0 > 40.0 | > 5.0 | GNSS fixes missing "
              "| > 40.0 |\n"),
      std::string::npos)
      << md;
  const std::string csv = read_file(dir / "runs.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + static_cast<long>(points.size()));
  EXPECT_NE(
      csv.find("static,cw,30.0,scalar,none,1,2,0.300,0.100,1.000,,0.500,1.000,scalar:16,1.250,2.500,2.000,4.000,1,"
               "GNSS fixes missing,1:0.980,1:44.5,3.0\n"),
      std::string::npos)
      << csv;
  const nlohmann::json table = report.to_json();
  ASSERT_EQ(table["rows"].size(), 2u);
  EXPECT_EQ(table["rows"][1]["first_failure_db"], "35.0");
  EXPECT_EQ(table["notes"]["points"], points.size());
}

}  // namespace
}  // namespace deepnav::bench
