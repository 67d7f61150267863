// The jamming sweep's points and the command each is run with: the J/S range, the order of
// the points, and every field of a point in its `deepnav bench jam-point` command (the
// sweep finds a point finished by its id, so a field missing from the command would make
// the sweep run it again forever).
#include "tools/bench/jam_sweep.hpp"

#include <gtest/gtest.h>

#include <functional>

#include "ins/input_error.hpp"
#include "tests/tools/deepnav_cli.hpp"
#include "tools/bench/child_process.hpp"

namespace deepnav::bench {
namespace {

using test::contains_words;
using test::has_flag;

TEST(JsRange, StepsFromFirstToLastInclusive) {
  EXPECT_EQ(parse_js_range("20:60:20"), (std::vector<double>{20.0, 40.0, 60.0}));
  EXPECT_EQ(parse_js_range("20:30:4"), (std::vector<double>{20.0, 24.0, 28.0}));
  EXPECT_EQ(parse_js_range("35"), std::vector<double>{35.0});
  // Steps that do not add up exactly in binary still land on the tenth of a dB.
  EXPECT_EQ(parse_js_range("0:0.3:0.1"), (std::vector<double>{0.0, 0.1, 0.2, 0.3}));
}

TEST(JsRange, RejectsWhatIsNotARange) {
  for (const char* bad : {"", "a:b:c", "60:20:5", "20:60:0", "20:60:-5", "-60:0:5", "20:130:5", "20:60:5:1", "20x"})
    EXPECT_THROW(parse_js_range(bad), InputError) << bad;
}

TEST(JamSweepPoints, OnePointPerJammerModeMitigationSeedAndJs) {
  JamSweepSettings s;
  s.scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/jam_short_test.yaml";
  s.jammers = "cw,pulsed";
  s.js = "20:30:10";
  s.mitigations = "none,excision";
  s.runs = 2;
  s.onset_s = 14.0;
  const std::vector<JamPoint> points = jam_sweep_points(s);
  ASSERT_EQ(points.size(), 2u * 2u * 2u * 2u);
  EXPECT_EQ(points[0].jammer, "cw");
  EXPECT_EQ(points[0].mitigation, "none");
  EXPECT_EQ(points[0].js_db, 20.0);
  EXPECT_EQ(points[1].js_db, 30.0);
  EXPECT_EQ(points[2].seed, points[0].seed + 1);  // the next run: the scenario's seed + 1
  EXPECT_EQ(points.back().jammer, "pulsed");
  EXPECT_EQ(points.back().mitigation, "excision");
  for (const auto& p : points) EXPECT_EQ(p.onset_s, 14.0);
}

TEST(JamSweepPoints, RejectsWhatTheSweepCannotRun) {
  JamSweepSettings s;
  s.scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/jam_short_test.yaml";
  s.onset_s = 14.0;
  const auto rejected = [&](const std::function<void(JamSweepSettings&)>& change) {
    JamSweepSettings bad = s;
    change(bad);
    EXPECT_THROW(jam_sweep_points(bad), InputError);
  };
  EXPECT_NO_THROW(jam_sweep_points(s));
  rejected([](JamSweepSettings& o) { o.jammers = "laser"; });
  rejected([](JamSweepSettings& o) { o.modes = "vector"; });
  rejected([](JamSweepSettings& o) { o.mitigations = "prayer"; });
  rejected([](JamSweepSettings& o) { o.runs = 0; });
  rejected([](JamSweepSettings& o) { o.onset_s = 1e6; });
  rejected([](JamSweepSettings& o) { o.scenario = "no_such_scenario.yaml"; });
  rejected([](JamSweepSettings& o) {  // Galileo on a GPS-only scenario
    o.systems = {GnssSystem::gps, GnssSystem::galileo};
  });
  rejected([](JamSweepSettings& o) {  // an aided mode on a scenario without an IMU
    o.scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/static_120s.yaml";
    o.modes = "tight";
    o.onset_s = 10.0;
  });
}

struct FieldChange {
  std::string field;
  std::function<void(JamPoint&)> change;
  std::vector<std::string> words;
};

TEST(JamPointCommand, NamesEveryFieldOfThePoint) {
  JamPoint base;
  base.scenario = "jam.yaml";
  base.jammer = "cw";
  base.js_db = 20.0;
  const std::vector<FieldChange> changes = {
      {"scenario", [](JamPoint& p) { p.scenario = "other.yaml"; }, {"--scenario", "other.yaml"}},
      {"jammer", [](JamPoint& p) { p.jammer = "chirp"; }, {"--jammer", "chirp"}},
      {"js_db", [](JamPoint& p) { p.js_db = 47.5; }, {"--js", "47.5"}},
      {"mode", [](JamPoint& p) { p.mode = "ultra"; }, {"--mode", "ultra"}},
      {"mitigation", [](JamPoint& p) { p.mitigation = "blanking"; }, {"--mitigation", "blanking"}},
      {"seed", [](JamPoint& p) { p.seed = 12345678901ULL; }, {"--seed", "12345678901"}},
      {"onset_s", [](JamPoint& p) { p.onset_s = 12.25; }, {"--onset", "12.25"}},
      {"coherent_ms", [](JamPoint& p) { p.long_integration.coherent_ms = 400; }, {"--coherent-ms", "400"}},
      {"noncoherent_ms", [](JamPoint& p) { p.long_integration.noncoherent_ms = 2000; }, {"--noncoherent-ms", "2000"}},
      {"assist_data_bits", [](JamPoint& p) { p.long_integration.assist_data_bits = true; }, {"--assist-data-bits"}},
      {"systems",
       [](JamPoint& p) {
         p.systems = {GnssSystem::gps, GnssSystem::galileo};
       },
       {"--systems", "gps,galileo"}},
  };
  for (const FieldChange& c : changes) {
    JamPoint p = base;
    c.change(p);
    const std::vector<std::string> argv = jam_point_command("deepnav", p, "/sweep");
    EXPECT_TRUE(contains_words(argv, c.words)) << c.field << ": " << shell_command_line(argv);
    EXPECT_TRUE(contains_words(argv, {"deepnav", "-q", "bench", "jam-point"}));
    EXPECT_TRUE(contains_words(argv, {"--out", "/sweep"}));
  }
  EXPECT_FALSE(has_flag(jam_point_command("deepnav", base, "/sweep"), "--assist-data-bits"));
  EXPECT_FALSE(has_flag(jam_point_command("deepnav", base, "/sweep"), "--systems"));
}

TEST(JamPointId, NamesBothSystemsAndKeepsTheGpsOnlyIdAsItWas) {
  JamPoint p;
  p.scenario = "data/scenarios/jam_static_gps_galileo_32s.yaml";
  p.jammer = "wideband";
  p.js_db = 42.5;
  p.mode = "tight";
  EXPECT_EQ(point_id(p), "jam_static_gps_galileo_32s_wideband_js042.5_tight_none_s1");
  p.systems = {GnssSystem::gps, GnssSystem::galileo};
  EXPECT_EQ(point_id(p), "jam_static_gps_galileo_32s_wideband_js042.5_tight_none_s1_gps-galileo");
}

}  // namespace
}  // namespace deepnav::bench
