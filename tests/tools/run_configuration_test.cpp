// The `deepnav run` a benchmark records (run_command) against the configuration it runs:
// every field set off its default shows in the command, and the command line itself
// (`deepnav run ... --print-config`, its own option definitions) reads the command back
// into exactly those fields.
#include "tools/bench/run_configuration.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <functional>
#include <set>

#include "ins/imu_model.hpp"
#include "ins/input_error.hpp"
#include "receiver/mitigation/mitigation_config.hpp"
#include "tests/tools/deepnav_cli.hpp"

namespace deepnav::bench {
namespace {

using test::contains_words;
using test::has_flag;
using test::run_deepnav;
using test::ScratchDir;

const std::string kNavFile = std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n";
const std::string kGradesFile = std::string(DEEPNAV_SOURCE_DIR) + "/data/imu_grades.yaml";

/// What `deepnav run` needs and nothing more: the IF file, its rate and the output folder.
RunConfiguration scalar_run() {
  RunConfiguration r;
  r.input = "signal.bin";
  r.sample_rate_hz = 4092000.0;
  r.out_dir = "products";
  return r;
}

/// An aided run with `deepnav run`'s own IMU defaults (grade, grades file, no lever arm).
RunConfiguration ultra_run(const std::string& imu_file) {
  RunConfiguration r = scalar_run();
  r.mode = "ultra";
  r.imu = {imu_file, "tactical", "data/imu_grades.yaml", {0.0, 0.0, 0.0}};
  return r;
}

/// One field set off its default: the words the command must carry for it, and the key
/// and value `deepnav run --print-config` must then show (the only key that changes).
struct FieldChange {
  std::string field;
  bool aided;  ///< changed on ultra_run (the IMU's fields), else on scalar_run
  std::function<void(RunConfiguration&)> change;
  std::vector<std::string> words;
  std::string key;
  std::string yaml_value;
};

std::vector<FieldChange> field_changes(const std::string& other_imu_file) {
  return {
      {"input",
       false,
       [](RunConfiguration& r) { r.input = "other.bin"; },
       {"--input", "other.bin"},
       "input",
       "other.bin"},
      {"format",
       false,
       [](RunConfiguration& r) { r.format = SampleFormat::ishort; },
       {"--format", "ishort"},
       "format",
       "ishort"},
      {"sample_rate_hz",
       false,
       [](RunConfiguration& r) { r.sample_rate_hz = 2.6e6; },
       {"--fs", "2600000"},
       "fs",
       "2600000"},
      {"if_hz", false, [](RunConfiguration& r) { r.if_hz = 1250.0; }, {"--if", "1250"}, "if", "1250"},
      {"week", false, [](RunConfiguration& r) { r.week = 2190; }, {"--week", "2190"}, "week", "2190"},
      {"systems",
       false,
       [](RunConfiguration& r) {
         r.systems = {GnssSystem::gps, GnssSystem::galileo};
       },
       {"--systems", "gps,galileo"},
       "systems",
       "gps,galileo"},
      {"iono_from",
       false,
       [](RunConfiguration& r) { r.iono_from = kNavFile; },
       {"--iono-from", kNavFile},
       "iono-from",
       kNavFile},
      {"ephemeris_from",
       false,
       [](RunConfiguration& r) { r.ephemeris_from = kNavFile; },
       {"--ephemeris-from", kNavFile},
       "ephemeris-from",
       kNavFile},
      {"truth",
       false,
       [](RunConfiguration& r) { r.truth = "truth.csv"; },
       {"--truth", "truth.csv"},
       "truth",
       "truth.csv"},
      {"mitigation",
       false,
       [](RunConfiguration& r) { r.mitigation = "excision"; },
       {"--mitigation", "excision"},
       "mitigation",
       "excision"},
      {"coherent_ms",
       false,
       [](RunConfiguration& r) { r.coherent_ms = 400; },
       {"--coherent-ms", "400"},
       "coherent-ms",
       "400"},
      {"noncoherent_ms",
       false,
       [](RunConfiguration& r) { r.noncoherent_ms = 2000; },
       {"--noncoherent-ms", "2000"},
       "noncoherent-ms",
       "2000"},
      {"assist_data_bits",
       false,
       [](RunConfiguration& r) { r.assist_data_bits = true; },
       {"--assist-data-bits"},
       "assist-data-bits",
       "true"},
      {"out_dir",
       false,
       [](RunConfiguration& r) { r.out_dir = "elsewhere"; },
       {"--out", "elsewhere"},
       "out",
       "elsewhere"},
      {"mode", true, [](RunConfiguration& r) { r.mode = "tight"; }, {"--mode", "tight"}, "mode", "tight"},
      {"imu.path",
       true,
       [other_imu_file](RunConfiguration& r) { r.imu.path = other_imu_file; },
       {"--imu", other_imu_file},
       "imu",
       other_imu_file},
      {"imu.grade",
       true,
       [](RunConfiguration& r) { r.imu.grade = "navigation"; },
       {"--imu-grade", "navigation"},
       "imu-grade",
       "navigation"},
      {"imu.grades_file",
       true,
       [](RunConfiguration& r) { r.imu.grades_file = kGradesFile; },
       {"--imu-grades-file", kGradesFile},
       "imu-grades-file",
       kGradesFile},
      {"imu.lever_arm_m",
       true,
       [](RunConfiguration& r) {
         r.imu.lever_arm_m = {0.5, 0.0, -0.3};
       },
       {"--imu-lever-arm", "0.5", "0", "-0.3"},
       "imu-lever-arm",
       "[0.5, 0, -0.3]"},
  };
}

/// The options `deepnav run` reads from the command (its effective configuration).
YAML::Node effective_run_options(const RunConfiguration& run) {
  std::vector<std::string> args = run_command(run);
  EXPECT_EQ(args.at(0), "deepnav");
  args.erase(args.begin());  // the program; run_deepnav puts this build's in
  args.push_back("--print-config");
  const test::CliResult r = run_deepnav(args);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return YAML::Load(r.output);
}

/// Two YAML values alike: numbers by value, lists element by element, the rest as text.
bool same_value(const YAML::Node& a, const YAML::Node& b) {
  if (!a.IsDefined() || !b.IsDefined()) return a.IsDefined() == b.IsDefined();  // a key not set: no value
  if (a.IsSequence() || b.IsSequence()) {
    if (!a.IsSequence() || !b.IsSequence() || a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_value(a[i], b[i])) return false;
    return true;
  }
  if (a.IsNull() || b.IsNull()) return a.IsNull() == b.IsNull();
  double x = 0.0, y = 0.0;
  if (YAML::convert<double>::decode(a, x) && YAML::convert<double>::decode(b, y)) return x == y;
  return a.as<std::string>() == b.as<std::string>();
}

/// The keys whose values differ between two effective configurations.
std::set<std::string> changed_keys(const YAML::Node& before, const YAML::Node& after) {
  // Read through const nodes: a key one of them lacks is then an undefined value, not an error.
  std::set<std::string> keys, changed;
  for (const auto& n : {before, after})
    for (const auto& kv : n) keys.insert(kv.first.as<std::string>());
  for (const auto& k : keys)
    if (!same_value(before[k], after[k])) changed.insert(k);
  return changed;
}

TEST(RunCommand, NamesEveryFieldSetOffItsDefault) {
  for (const FieldChange& c : field_changes("other_imu.csv")) {
    RunConfiguration run = c.aided ? ultra_run("imu.csv") : scalar_run();
    c.change(run);
    const std::vector<std::string> argv = run_command(run);
    EXPECT_TRUE(contains_words(argv, c.words)) << c.field << ": " << shell_command_line(argv);
  }
}

TEST(RunCommand, ScalarModeGivesNoImuArguments) {
  RunConfiguration run = scalar_run();
  run.imu = {"imu.csv", "navigation", kGradesFile, {1.0, 2.0, 3.0}};
  const std::vector<std::string> argv = run_command(run);
  EXPECT_FALSE(has_flag(argv, "--mode"));
  EXPECT_FALSE(has_flag(argv, "--imu"));
  EXPECT_FALSE(has_flag(argv, "--imu-lever-arm"));
}

TEST(RunCommand, AidedModeWithoutImuFileIsRefused) {
  RunConfiguration run = ultra_run("");
  EXPECT_THROW(run_command(run), InputError);
}

TEST(RunCommand, OmitsTheFilesNotGiven) {
  const std::vector<std::string> argv = run_command(scalar_run());
  for (const char* option : {"--week", "--iono-from", "--ephemeris-from", "--truth", "--assist-data-bits"})
    EXPECT_FALSE(has_flag(argv, option)) << option;
}

// The command line's own option definitions read each recorded command back: the field
// changed, and nothing else, differs from the configuration without it.
TEST(RunCommand, DeepnavRunReadsBackExactlyTheConfiguration) {
  const ScratchDir dir("run_command_test");
  const std::string imu = dir / "imu.csv", other_imu = dir / "other_imu.csv";
  for (const auto& path : {imu, other_imu}) std::ofstream(path) << "t_s\n";  // --imu must name a file
  const YAML::Node scalar = effective_run_options(scalar_run());
  const YAML::Node ultra = effective_run_options(ultra_run(imu));
  EXPECT_EQ(changed_keys(scalar, ultra), (std::set<std::string>{"mode", "imu", "imu-lever-arm"}));
  for (const FieldChange& c : field_changes(other_imu)) {
    RunConfiguration run = c.aided ? ultra_run(imu) : scalar_run();
    c.change(run);
    const YAML::Node changed = effective_run_options(run);
    EXPECT_EQ(changed_keys(c.aided ? ultra : scalar, changed), std::set<std::string>{c.key}) << c.field;
    EXPECT_TRUE(same_value(changed[c.key], YAML::Load(c.yaml_value))) << c.field << ": " << YAML::Dump(changed[c.key]);
  }
}

TEST(RunSessionConfig, IsTheConfigurationTheCommandDescribes) {
  RunConfiguration run = ultra_run("imu.csv");
  run.imu.grade = "navigation";
  run.imu.grades_file = kGradesFile;
  run.imu.lever_arm_m = {0.5, 0.0, -0.3};
  run.week = 2190;
  run.iono_from = kNavFile;
  run.ephemeris_from = kNavFile;
  run.mitigation = "excision";
  run.coherent_ms = 400;
  run.noncoherent_ms = 2000;
  run.assist_data_bits = true;
  const aiding::NavigationSessionConfig c = run_session_config(run);
  EXPECT_EQ(c.navigator.mode, aiding::NavMode::ultra);
  EXPECT_EQ(c.navigator.receiver.reference_week, 2190);
  EXPECT_EQ(c.mitigation.mode, MitigationMode::excision);
  EXPECT_EQ(c.navigator.ultra.long_integration.coherent_ms, 400);
  EXPECT_EQ(c.navigator.ultra.long_integration.noncoherent_ms, 2000);
  EXPECT_TRUE(c.navigator.ultra.long_integration.assist_data_bits);
  // The lever arm from the antenna to the IMU, as the scenario and the command give it;
  // the navigator's is the other way round.
  EXPECT_EQ(c.navigator.lever_arm_imu_to_antenna_b_m, Eigen::Vector3d(-0.5, 0.0, 0.3));
  EXPECT_EQ(c.navigator.imu.gyro.bias_sigma, load_imu_grade(kGradesFile, "navigation").model.gyro.bias_sigma);
  EXPECT_TRUE(c.assisted_iono.has_value());
  EXPECT_TRUE(c.assisted_ephemerides.has_value());

  const aiding::NavigationSessionConfig scalar = run_session_config(scalar_run());
  EXPECT_EQ(scalar.navigator.mode, aiding::NavMode::scalar);
  EXPECT_FALSE(scalar.assisted_iono.has_value());
  EXPECT_FALSE(scalar.assisted_ephemerides.has_value());
  EXPECT_EQ(scalar.mitigation.mode, MitigationMode::none);
}

TEST(RunSourceOptions, ReadTheFileAsTheCommandSays) {
  RunConfiguration run = scalar_run();
  run.format = SampleFormat::ishort;
  run.if_hz = 1250.0;
  const FileSampleSourceOptions o = run_source_options(run);
  EXPECT_EQ(o.path, "signal.bin");
  EXPECT_EQ(o.format, SampleFormat::ishort);
  EXPECT_EQ(o.sample_rate_hz, 4092000.0);
  EXPECT_EQ(o.intermediate_frequency_hz, 1250.0);
}

}  // namespace
}  // namespace deepnav::bench
