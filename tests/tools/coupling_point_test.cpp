// The coupling benchmark's point command (what --list-commands prints) against the point
// it makes: every setting off its default shows in the command, and `deepnav bench
// coupling` reads the command back into the very settings the point records (it then
// finds that point finished instead of refusing it as made with other settings).
#include "tools/bench/coupling_point.hpp"

#include <gtest/gtest.h>

#include <functional>

#include "ins/input_error.hpp"
#include "tests/tools/deepnav_cli.hpp"
#include "tools/bench/bench_report.hpp"

namespace deepnav::bench {
namespace {

using test::contains_words;
using test::run_deepnav;
using test::ScratchDir;

CouplingPoint default_point() { return {"land-circle", 0, {}}; }

struct SettingChange {
  std::string setting;
  std::function<void(CouplingPoint&)> change;
  std::vector<std::string> words;  ///< what the command must carry for it
};

std::vector<SettingChange> setting_changes() {
  const std::string other_scenario = source_tree_path("data/scenarios/land_circle_aided_90s_open_sky.yaml");
  return {
      {"trajectory", [](CouplingPoint& p) { p.trajectory = "air-s-x2"; }, {"--trajectories", "air-s-x2"}},
      {"run", [](CouplingPoint& p) { p.run = 7; }, {"--first-run", "7", "--runs", "1"}},
      {"modes",
       [](CouplingPoint& p) {
         p.settings.modes = {"ultra", "scalar"};
       },
       {"--modes", "ultra,scalar"}},
      {"errors", [](CouplingPoint& p) { p.settings.errors = "urban"; }, {"--errors", "urban"}},
      {"duration_s", [](CouplingPoint& p) { p.settings.duration_s = 180.5; }, {"--duration", "180.5"}},
      {"imu_grade", [](CouplingPoint& p) { p.settings.imu_grade = "tactical"; }, {"--imu-grade", "tactical"}},
      {"base_scenario",
       [other_scenario](CouplingPoint& p) { p.settings.base_scenario = other_scenario; },
       {"--scenario", other_scenario}},
      {"seed", [](CouplingPoint& p) { p.settings.seed = 42; }, {"--seed", "42"}},
      {"atmosphere.ionosphere",
       [](CouplingPoint& p) { p.settings.atmosphere.ionosphere = IonosphereModel::none; },
       {"--ionosphere", "none"}},
      {"atmosphere.troposphere",
       [](CouplingPoint& p) { p.settings.atmosphere.troposphere = TroposphereModel::none; },
       {"--troposphere", "none"}},
      {"filter_troposphere", [](CouplingPoint& p) { p.settings.filter_troposphere = true; }, {"--filter-troposphere"}},
      {"filter_ionosphere", [](CouplingPoint& p) { p.settings.filter_ionosphere = true; }, {"--filter-ionosphere"}},
      {"systems",
       [](CouplingPoint& p) {
         p.settings.systems = {GnssSystem::gps, GnssSystem::galileo};
       },
       {"--systems", "gps,galileo"}},
  };
}

TEST(CouplingPointCommand, NamesEverySettingOffItsDefault) {
  for (const SettingChange& c : setting_changes()) {
    CouplingPoint p = default_point();
    c.change(p);
    const std::vector<std::string> argv = coupling_point_command("deepnav", p, "/sweep");
    EXPECT_TRUE(contains_words(argv, c.words)) << c.setting << ": " << shell_command_line(argv);
    EXPECT_TRUE(contains_words(argv, {"--out", "/sweep"}));
  }
}

TEST(CouplingPointSettings, RecordEverySettingThePointDependsOn) {
  const nlohmann::json base = coupling_point_settings(default_point());
  for (const SettingChange& c : setting_changes()) {
    if (c.setting == "modes") continue;  // every mode is its own record inside the point
    CouplingPoint p = default_point();
    c.change(p);
    EXPECT_NE(coupling_point_settings(p), base) << c.setting;
  }
}

TEST(CouplingPointSettings, SeedFollowsRunAndTrajectory) {
  CouplingPoint p = default_point();
  p.run = 2;
  p.trajectory = "air-circle";  // fifth in the list
  EXPECT_EQ(coupling_point_settings(p)["seed"], 300u + 2000u + 4u);
  EXPECT_EQ(coupling_point_name(p), "air-circle_r002");
  EXPECT_THROW(coupling_seed_index("sea-circle"), InputError);
}

/// A finished point made with `made`'s settings, with an (empty) record per mode.
void write_finished_point(const std::string& out_dir, const CouplingPoint& made) {
  nlohmann::json point = coupling_point_settings(made);
  for (const auto& m : made.settings.modes) point["modes"][m] = nlohmann::json::object();
  write_coupling_point(out_dir, made, point);
}

/// `deepnav bench coupling` with `p`'s command and --list-commands.
test::CliResult list_with_command_of(const CouplingPoint& p, const std::string& out_dir) {
  std::vector<std::string> args = coupling_point_command("deepnav", p, out_dir);
  args.erase(args.begin());
  args.push_back("--list-commands");
  return run_deepnav(args);
}

TEST(CouplingPointCommand, DeepnavReadsBackThePointsOwnSettings) {
  for (const SettingChange& c : setting_changes()) {
    const ScratchDir dir("coupling_point_test");
    CouplingPoint p = default_point();
    c.change(p);
    write_finished_point(dir.path().string(), p);
    // Read back into the same settings: the point is finished, nothing is left to list.
    const test::CliResult same = list_with_command_of(p, dir.path().string());
    EXPECT_EQ(same.exit_code, 0) << c.setting << ": " << same.output;
    EXPECT_EQ(same.output, "") << c.setting;
    // The default point's command over that point: refused as made with other settings
    // (or, for another trajectory or run, another point still to run).
    const test::CliResult other = list_with_command_of(default_point(), dir.path().string());
    EXPECT_TRUE(other.exit_code != 0 || other.output.find("bench coupling") != std::string::npos)
        << c.setting << ": " << other.output;
  }
}

}  // namespace
}  // namespace deepnav::bench
