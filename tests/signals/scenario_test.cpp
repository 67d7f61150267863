#include "signals/sim/scenario.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "signals/sim/multipath_presets.hpp"

namespace deepnav {
namespace {

const std::string kRoot = DEEPNAV_SOURCE_DIR;

Scenario parse(const std::string& text) { return parse_scenario(text, "test.yaml", kRoot, kRoot); }

/// Expects parsing to fail with a message that contains every fragment.
void expect_error(const std::string& text, std::initializer_list<const char*> fragments) {
  try {
    parse(text);
    FAIL() << "expected an error for:\n" << text;
  } catch (const std::invalid_argument& e) {
    for (const char* f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
  }
}

const char* kMinimal = "start_time: \"2022-01-01T02:00:00\"\nduration_s: 10\n";

TEST(Scenario, MinimalScenarioGetsDefaults) {
  const Scenario s = parse(kMinimal);
  EXPECT_EQ(s.start_time.week, 2190);
  EXPECT_NEAR(s.start_time.sow, 518400.0 + 7200.0, 1e-9);
  EXPECT_EQ(s.duration_s, 10.0);
  EXPECT_EQ(s.sample_rate_hz, 4.092e6);
  EXPECT_EQ(s.format, SampleFormat::ibyte);
  EXPECT_EQ(s.trajectory.preset, "static");
  EXPECT_NE(s.nav_file.find("brdc0010.22n"), std::string::npos);
  EXPECT_EQ(s.max_satellites, 12);
}

TEST(Scenario, BundledScenariosLoad) {
  for (const char* name : {"default.yaml", "gnss_sdr_static.yaml"}) {
    const Scenario s = load_scenario(kRoot + "/data/scenarios/" + name, kRoot);
    EXPECT_GT(s.duration_s, 0.0) << name;
  }
}

TEST(Scenario, FullScenarioRoundTripsThroughYaml) {
  const Scenario s = parse(R"(
start_time: {week: 2190, sow: 525600}
duration_s: 2.5
sample_rate_hz: 8184000
if_hz: 1000000
format: byte
adc: {bits: 2, agc: true, agc_time_constant_s: 0.005}
trajectory: {preset: land-circle, start: {lat_deg: 35, lon_deg: 127, height_m: 10}, heading_deg: 90}
elevation_mask_deg: 15
prns: [1, 3, 7]
cn0: {model: elevation, zenith_dbhz: 50, horizon_dbhz: 35, per_prn: {7: 30}, ramp: {start_s: 1, end_s: 2, delta_db: -10}}
receiver_clock: {bias_s: 0.001, drift_ppm: 1.5, oscillator: tcxo}
ionosphere: false
seed: 42
jammers:
  - {type: cw, js_db: 40, offset_hz: 1000}
  - {type: chirp, js_db: 30, bandwidth_hz: 2000000, sweep_period_s: 0.0001}
outages: [{start_s: 1, end_s: 2, prns: [3]}]
imu: {grade: tactical, rate_hz: 200, lever_arm_m: [0.5, 0, -1]}
truth_rate_hz: 50
)");
  EXPECT_EQ(s.format, SampleFormat::byte);
  EXPECT_EQ(s.adc.bits, 2);
  EXPECT_EQ(s.prns.size(), 3u);
  EXPECT_NEAR(s.clock.drift_sps, 1.5e-6, 1e-15);
  EXPECT_GT(s.clock.h0, 0.0);
  EXPECT_EQ(s.jammers.size(), 2u);
  EXPECT_EQ(s.cn0.per_prn_dbhz.at(7), 30.0);
  const Scenario back = parse(scenario_to_yaml(s));
  EXPECT_EQ(back.start_time.week, s.start_time.week);
  EXPECT_DOUBLE_EQ(back.start_time.sow, s.start_time.sow);
  EXPECT_DOUBLE_EQ(back.sample_rate_hz, s.sample_rate_hz);
  EXPECT_DOUBLE_EQ(back.if_hz, s.if_hz);
  EXPECT_EQ(back.format, s.format);
  EXPECT_EQ(back.trajectory.preset, "land-circle");
  EXPECT_NEAR(back.trajectory.heading_rad, s.trajectory.heading_rad, 1e-12);
  EXPECT_EQ(back.prns, s.prns);
  EXPECT_DOUBLE_EQ(back.clock.h0, s.clock.h0);
  EXPECT_EQ(back.jammers.size(), 2u);
  EXPECT_DOUBLE_EQ(back.jammers[1].sweep_period_s, 1e-4);
  EXPECT_EQ(back.outages.size(), 1u);
  EXPECT_EQ(back.seed, 42u);
  EXPECT_FALSE(back.ionosphere);
  EXPECT_TRUE(back.imu.enabled);
  EXPECT_EQ(back.imu.grade, "tactical");
  EXPECT_EQ(back.imu.rate_hz, 200.0);
  EXPECT_EQ(back.imu.lever_arm_m[2], -1.0);
}

TEST(Scenario, BadInputNamesTheField) {
  expect_error("duration_s: 10\n", {"start_time"});
  expect_error("start_time: \"2022-01-01T02:00:00\"\nduration_s: -3\n", {"duration_s", "positive"});
  expect_error("start_time: \"2022-13-01T02:00:00\"\nduration_s: 1\n", {"start_time"});
  expect_error(std::string(kMinimal) + "format: int4\n", {"format", "ibyte"});
  expect_error(std::string(kMinimal) + "sample_rate_hz: 4092500\n", {"sample_rate_hz", "1000"});
  expect_error(std::string(kMinimal) + "durration_s: 4\n", {"durration_s", "unknown field"});
  expect_error(std::string(kMinimal) + "jammers: [{type: cw, js_db: 130}]\n", {"jammers[0].js_db", "out of range"});
  expect_error(std::string(kMinimal) + "jammers: [{type: laser, js_db: 10}]\n", {"jammers[0].type"});
  expect_error(std::string(kMinimal) + "nav_file: data/nope.22n\n", {"nav_file", "does not exist"});
  expect_error(std::string(kMinimal) + "format: byte\n", {"if_hz"});
  expect_error(std::string(kMinimal) + "adc: {bits: 12}\n", {"adc.bits"});
  expect_error(std::string(kMinimal) + "truth_rate_hz: 3\n", {"truth_rate_hz"});
  expect_error(std::string(kMinimal) + "cn0: {model: fancy}\n", {"cn0.model"});
  expect_error(std::string(kMinimal) + "imu: {grade: wishful}\n", {"imu.grade", "tactical"});
  expect_error(std::string(kMinimal) + "imu: {lever_arm_m: [1, 2]}\n", {"imu.lever_arm_m"});
  expect_error("start_time: [unclosed\n", {"test.yaml"});
  expect_error("", {"test.yaml"});
}

// Found by fuzzing (tests/fuzz/scenario_fuzzer.cpp): a key that is a list escaped as
// yaml-cpp's "bad conversion", naming neither the file nor the field.
TEST(Scenario, KeysThatAreNotNamesAreErrors) {
  expect_error(std::string(kMinimal) + "imu: {grade: tactical, lever_arm_m: 0.8,[. .3, 0.4]}\n",
               {"test.yaml:3", "field 'imu'", "expected field names as keys"});
  expect_error(std::string(kMinimal) + "? [a, b]\n: 1\n", {"test.yaml:3", "expected field names as keys"});
  expect_error(std::string(kMinimal) + "~: 1\n", {"test.yaml:3", "an empty key"});
}

// Found by fuzzing (tests/fuzz/scenario_fuzzer.cpp): a date-form start time in year 3738
// (GPS week 91727) was accepted, and the scenario written beside the outputs, which has
// it as {week, sow}, then failed to read ("start_time.week out of range").
TEST(Scenario, StartTimeBoundsAgreeInBothForms) {
  expect_error("start_time: \"3738-01-01T02:00:00\"\nduration_s: 1\n", {"start_time", "GPS week 91727", "10000"});
  expect_error("start_time: {week: 10001, sow: 0}\nduration_s: 1\n", {"start_time.week", "out of range"});
  const Scenario late = parse_scenario("start_time: \"2171-08-01T00:00:00\"\nduration_s: 1\n", "test.yaml",
                                       DEEPNAV_SOURCE_DIR, DEEPNAV_SOURCE_DIR);
  EXPECT_EQ(late.start_time.week, 9995);
  EXPECT_NO_THROW(parse_scenario(scenario_to_yaml(late), "written.yaml", DEEPNAV_SOURCE_DIR, DEEPNAV_SOURCE_DIR));
}

TEST(Scenario, APathTooLongToLookUpIsAnErrorNamingTheField) {
  // Found by the scenario fuzzer: a file name past the system's limit made the existence
  // check throw std::filesystem::filesystem_error, which no reader of scenarios expects.
  const std::string name(5000, 'x');
  expect_error("start_time: \"2022-01-01T02:00:00\"\nduration_s: 1\nnav_file: " + name + "\n",
               {"nav_file", "cannot be looked up"});
  expect_error("start_time: \"2022-01-01T02:00:00\"\nduration_s: 1\ntrajectory: {file: " + name + "}\n",
               {"trajectory.file", "cannot be looked up"});
  expect_error("start_time: \"2022-01-01T02:00:00\"\nduration_s: 1\nimu: {grades_file: " + name + "}\n",
               {"imu", "cannot be looked up"});
}

TEST(Scenario, ErrorsDefaultToNoneAndPresetsFillEveryField) {
  EXPECT_EQ(parse(kMinimal).errors, error_preset("none"));
  EXPECT_EQ(parse(std::string(kMinimal) + "errors: {preset: none}\n").errors, error_preset("none"));
  const ErrorSpec none = error_preset("none");
  EXPECT_EQ(none.ionosphere.model, IonosphereTruthSpec::Model::klobuchar);
  EXPECT_EQ(none.ionosphere.vtec_scale, 1.0);
  EXPECT_EQ(none.troposphere.model, TroposphereTruthSpec::Model::saastamoinen_standard);
  EXPECT_FALSE(none.orbit_clock.any());
  EXPECT_EQ(none.antenna.pattern, AntennaSpec::Pattern::isotropic);
  for (const std::string& name : error_preset_names()) {
    const Scenario s = parse(std::string(kMinimal) + "errors: {preset: " + name + "}\n");
    EXPECT_EQ(s.errors, error_preset(name)) << name;
    EXPECT_EQ(s.errors.preset, name);
  }
  const ErrorSpec open = error_preset("open-sky");
  EXPECT_EQ(open.ionosphere.model, IonosphereTruthSpec::Model::thin_shell);
  EXPECT_EQ(open.troposphere.model, TroposphereTruthSpec::Model::site);
  EXPECT_TRUE(open.orbit_clock.any());
  EXPECT_EQ(open.antenna.pattern, AntennaSpec::Pattern::patch);
}

TEST(Scenario, ExplicitErrorFieldsOverrideThePreset) {
  const Scenario s = parse(std::string(kMinimal) + R"(errors:
  preset: open-sky
  ionosphere: {vtec_scale: 1.5, shell_height_km: 350}
  troposphere: {mapping: black-eisner, temperature_c: -5.5}
  orbit_clock: {clock_m: 0}
  antenna: {pattern: isotropic}
)");
  ErrorSpec expected = error_preset("open-sky");
  expected.ionosphere.vtec_scale = 1.5;
  expected.ionosphere.shell_height_m = 350e3;
  expected.troposphere.mapping = TroposphereTruthSpec::Mapping::black_eisner;
  expected.troposphere.temperature_c = -5.5;
  expected.orbit_clock.clock_m = 0.0;
  expected.antenna.pattern = AntennaSpec::Pattern::isotropic;
  EXPECT_EQ(s.errors, expected);
  // Without a preset the overrides apply to none.
  const Scenario n = parse(std::string(kMinimal) + "errors: {orbit_clock: {radial_m: 0.4}}\n");
  EXPECT_EQ(n.errors.preset, "none");
  EXPECT_EQ(n.errors.orbit_clock.radial_m, 0.4);
  EXPECT_EQ(n.errors.ionosphere, error_preset("none").ionosphere);
}

TEST(Scenario, ErrorSettingsRoundTripThroughYaml) {
  for (const std::string& extra :
       {std::string(""), std::string("errors: {preset: urban}\n"),
        std::string(
            "errors:\n  preset: suburban\n  ionosphere: {model: klobuchar, vtec_scale: 0.7, day_vtec_tecu: 33.3, "
            "night_vtec_tecu: 2.5, shell_height_km: 425.5, disturbance_rms: 0.07}\n  troposphere: {model: site, "
            "pressure_hpa: 998.4, temperature_c: 31.7, relative_humidity: 0.91, wet_random_walk_m_per_sqrt_h: "
            "0.021, mapping: black-eisner}\n  orbit_clock: {radial_m: 0.25, along_m: 1.3, cross_m: 0.45, "
            "clock_m: 0.65, correlation_time_s: 5400}\n  antenna: {pattern: patch, gain_10deg_db: -6.5, "
            "gain_horizon_db: -12.25}\n")}) {
    const Scenario s = parse(std::string(kMinimal) + extra);
    const std::string yaml = scenario_to_yaml(s);
    EXPECT_NE(yaml.find("errors:"), std::string::npos);
    const Scenario back = parse(yaml);
    EXPECT_EQ(back.errors, s.errors) << yaml;
    EXPECT_EQ(scenario_to_yaml(back), yaml);
  }
}

TEST(Scenario, BadErrorSettingsNameTheField) {
  const std::string m = kMinimal;
  expect_error(m + "errors: {preset: jungle}\n", {"test.yaml:3", "errors.preset", "open-sky"});
  expect_error(m + "errors: {presets: none}\n", {"errors.presets", "unknown field"});
  expect_error(m + "errors:\n  ionosphere: {modle: klobuchar}\n",
               {"test.yaml:4", "errors.ionosphere.modle", "unknown field"});
  expect_error(m + "errors: {ionosphere: {model: iri}}\n", {"errors.ionosphere.model", "thin-shell"});
  expect_error(m + "errors: {ionosphere: {vtec_scale: -1}}\n", {"errors.ionosphere.vtec_scale", "out of range"});
  expect_error(m + "errors: {ionosphere: {night_vtec_tecu: 80}}\n",
               {"errors.ionosphere.night_vtec_tecu", "day_vtec_tecu"});
  expect_error(m + "errors: {ionosphere: {shell_height_km: 50}}\n",
               {"errors.ionosphere.shell_height_km", "out of range"});
  expect_error(m + "errors: {troposphere: {relative_humidity: 1.5}}\n",
               {"errors.troposphere.relative_humidity", "out of range"});
  expect_error(m + "errors: {troposphere: {mapping: gmf}}\n", {"errors.troposphere.mapping", "niell"});
  expect_error(m + "errors: {troposphere: {pressure: 1000}}\n", {"errors.troposphere.pressure", "unknown field"});
  expect_error(m + "errors: {orbit_clock: {radial_m: -0.1}}\n", {"errors.orbit_clock.radial_m", "out of range"});
  expect_error(m + "errors: {orbit_clock: {correlation_time_s: 1}}\n", {"errors.orbit_clock.correlation_time_s"});
  expect_error(m + "errors: {orbit_clock: {sisre_m: 1}}\n", {"errors.orbit_clock.sisre_m", "unknown field"});
  expect_error(m + "errors: {antenna: {pattern: helix}}\n", {"errors.antenna.pattern", "patch"});
  expect_error(m + "errors: {antenna: {gain_10deg_db: -12}}\n", {"errors.antenna.gain_10deg_db", "gain_horizon_db"});
  expect_error(m + "errors: {antenna: {gain_10deg_db: 3}}\n", {"errors.antenna.gain_10deg_db", "out of range"});
  expect_error(m + "errors: open-sky\n", {"errors", "mapping"});
}

TEST(Scenario, MultipathParsesAndRoundTrips) {
  EXPECT_EQ(parse(kMinimal).errors.multipath.model, MultipathSpec::Model::none);
  EXPECT_EQ(parse(std::string(kMinimal) + "errors: {multipath: {model: none}}\n").errors.multipath.model,
            MultipathSpec::Model::none);
  const Scenario g = parse(std::string(kMinimal) +
                           "errors: {multipath: {model: ground, antenna_height_m: 2, reflection_coefficient: 0.4, "
                           "below_horizon_gain_db: -12}}\n");
  EXPECT_EQ(g.errors.multipath.model, MultipathSpec::Model::ground);
  EXPECT_EQ(g.errors.multipath.antenna_height_m, 2.0);
  EXPECT_EQ(g.errors.multipath.reflection_coefficient, 0.4);
  EXPECT_EQ(g.errors.multipath.below_horizon_gain_db, -12.0);
  const Scenario g_back = parse(scenario_to_yaml(g));
  EXPECT_EQ(g_back.errors.multipath.model, MultipathSpec::Model::ground);
  EXPECT_EQ(g_back.errors.multipath.antenna_height_m, 2.0);
  EXPECT_EQ(g_back.errors.multipath.below_horizon_gain_db, -12.0);

  const Scenario l = parse(
      std::string(kMinimal) +
      "errors:\n  multipath:\n    model: land-mobile\n    echoes: 4\n    echo_power_db: -8\n    echo_rician_k: 2\n"
      "    mean_excess_delay_m: 40\n    echo_lifetime_s: 3\n    blocked_probability: 0.3\n"
      "    mean_blocked_s: 1.5\n    blocked_attenuation_db: 22\n");
  const Scenario l_back = parse(scenario_to_yaml(l));
  for (const Scenario* s : {&l, &l_back}) {
    const MultipathSpec& m = s->errors.multipath;
    EXPECT_EQ(m.model, MultipathSpec::Model::land_mobile);
    EXPECT_EQ(m.echoes, 4);
    EXPECT_EQ(m.echo_power_db, -8.0);
    EXPECT_EQ(m.echo_rician_k, 2.0);
    EXPECT_EQ(m.mean_excess_delay_m, 40.0);
    EXPECT_EQ(m.echo_lifetime_s, 3.0);
    EXPECT_EQ(m.blocked_probability, 0.3);
    EXPECT_EQ(m.mean_blocked_s, 1.5);
    EXPECT_EQ(m.blocked_attenuation_db, 22.0);
  }
  // An environment, as shorthand or as the base that the keys given override.
  EXPECT_EQ(parse(std::string(kMinimal) + "errors: {multipath: urban}\n").errors.multipath.echoes,
            multipath_for_environment("urban").echoes);
  const Scenario e =
      parse(std::string(kMinimal) + "errors: {multipath: {environment: suburban, blocked_probability: 0.5}}\n");
  EXPECT_EQ(e.errors.multipath.model, MultipathSpec::Model::land_mobile);
  EXPECT_EQ(e.errors.multipath.blocked_probability, 0.5);
  EXPECT_EQ(e.errors.multipath.echo_power_db, multipath_for_environment("suburban").echo_power_db);
  EXPECT_EQ(parse(std::string(kMinimal) + "errors: {multipath: open-sky}\n").errors.multipath.model,
            MultipathSpec::Model::ground);
  EXPECT_NE(scenario_to_yaml(parse(kMinimal)).find("multipath: {model: none}"), std::string::npos);
}

TEST(Scenario, BadMultipathNamesTheField) {
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: rain}}\n",
               {"test.yaml:3", "multipath.model", "land-mobile"});
  expect_error(std::string(kMinimal) + "errors: {multipath: downtown}\n", {"multipath", "urban"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: ground, echoes: 3}}\n",
               {"multipath.echoes", "land-mobile"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: land-mobile, antenna_height_m: 3}}\n",
               {"multipath.antenna_height_m", "ground"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: none, echoes: 2}}\n", {"multipath.echoes"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: land-mobile, echoes: 9}}\n",
               {"multipath.echoes", "out of range"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: land-mobile, blocked_probability: 1.2}}\n",
               {"multipath.blocked_probability", "out of range"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: ground, reflection_coefficient: 1.5}}\n",
               {"multipath.reflection_coefficient"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: ground, height_m: 3}}\n",
               {"multipath.height_m", "unknown field"});
  expect_error(std::string(kMinimal) + "errors: {multipath: {model: ground, environment: urban}}\n",
               {"multipath", "not both"});
}

TEST(Scenario, MissingFileIsReported) {
  EXPECT_THROW(load_scenario("/nonexistent/scenario.yaml"), std::invalid_argument);
}

TEST(Scenario, ImpossibleStartTimesAreErrors) {
  // Accepted before: Feb 31 (read as Mar 3), a negative hour, trailing text.
  for (const char* bad :
       {"2022-02-31T02:00:00", "2022-01-01T-3:00:00", "2021-02-29T00:00:00", "2022-01-01T24:00:00",
        "2022-01-01T02:00:00junk", "2022-1-1T02:00:00", "1979-12-31T00:00:00", "2022-01-01T02:60:00"}) {
    expect_error(std::string("start_time: \"") + bad + "\"\nduration_s: 1\n", {"test.yaml:1", "start_time", bad});
  }
  EXPECT_EQ(parse("start_time: \"2024-02-29T23:59:59.5\"\nduration_s: 1\n").start_time.week, 2303);
  EXPECT_EQ(parse("start_time: \"2022-01-01 02:00:00\"\nduration_s: 1\n").start_time.week, 2190);
}

TEST(Scenario, DuplicateKeysAreErrors) {
  expect_error(std::string(kMinimal) + "duration_s: 20\n",
               {"test.yaml:3: key 'duration_s' appears twice", "lines 2 and 3"});
  expect_error(std::string(kMinimal) + "cn0: {dbhz: 40, dbhz: 45}\n", {"key 'dbhz' appears twice"});
}

TEST(Scenario, NotARegularFileIsAnErrorAtOnce) {
  // /dev/zero used to be read until memory ran out.
  try {
    load_scenario("/dev/zero");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scenario file '/dev/zero' is a device"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace deepnav
