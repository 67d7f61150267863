#include "signals/scenario.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "signals/multipath_presets.hpp"

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

TEST(Scenario, MultipathSectionParsesAndRoundTrips) {
  EXPECT_EQ(parse(kMinimal).multipath.model, MultipathSpec::Model::none);
  EXPECT_EQ(parse(std::string(kMinimal) + "multipath: {model: none}\n").multipath.model, MultipathSpec::Model::none);
  const Scenario g = parse(std::string(kMinimal) +
                           "multipath: {model: ground, antenna_height_m: 2, reflection_coefficient: 0.4, "
                           "below_horizon_gain_db: -12}\n");
  EXPECT_EQ(g.multipath.model, MultipathSpec::Model::ground);
  EXPECT_EQ(g.multipath.antenna_height_m, 2.0);
  EXPECT_EQ(g.multipath.reflection_coefficient, 0.4);
  EXPECT_EQ(g.multipath.below_horizon_gain_db, -12.0);
  const Scenario g_back = parse(scenario_to_yaml(g));
  EXPECT_EQ(g_back.multipath.model, MultipathSpec::Model::ground);
  EXPECT_EQ(g_back.multipath.antenna_height_m, 2.0);
  EXPECT_EQ(g_back.multipath.below_horizon_gain_db, -12.0);

  const Scenario l = parse(std::string(kMinimal) +
                           "multipath:\n  model: land-mobile\n  echoes: 4\n  echo_power_db: -8\n  echo_rician_k: 2\n"
                           "  mean_excess_delay_m: 40\n  echo_lifetime_s: 3\n  blocked_probability: 0.3\n"
                           "  mean_blocked_s: 1.5\n  blocked_attenuation_db: 22\n");
  const Scenario l_back = parse(scenario_to_yaml(l));
  for (const Scenario* s : {&l, &l_back}) {
    const MultipathSpec& m = s->multipath;
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
  EXPECT_EQ(parse(std::string(kMinimal) + "multipath: urban\n").multipath.echoes, multipath_for_environment("urban").echoes);
  const Scenario e = parse(std::string(kMinimal) + "multipath: {environment: suburban, blocked_probability: 0.5}\n");
  EXPECT_EQ(e.multipath.model, MultipathSpec::Model::land_mobile);
  EXPECT_EQ(e.multipath.blocked_probability, 0.5);
  EXPECT_EQ(e.multipath.echo_power_db, multipath_for_environment("suburban").echo_power_db);
  EXPECT_EQ(parse(std::string(kMinimal) + "multipath: open-sky\n").multipath.model, MultipathSpec::Model::ground);
  EXPECT_EQ(scenario_to_yaml(parse(kMinimal)).find("multipath:"), std::string::npos);
}

TEST(Scenario, BadMultipathNamesTheField) {
  expect_error(std::string(kMinimal) + "multipath: {model: rain}\n", {"test.yaml:3", "multipath.model", "land-mobile"});
  expect_error(std::string(kMinimal) + "multipath: downtown\n", {"multipath", "urban"});
  expect_error(std::string(kMinimal) + "multipath: {model: ground, echoes: 3}\n", {"multipath.echoes", "land-mobile"});
  expect_error(std::string(kMinimal) + "multipath: {model: land-mobile, antenna_height_m: 3}\n",
               {"multipath.antenna_height_m", "ground"});
  expect_error(std::string(kMinimal) + "multipath: {model: none, echoes: 2}\n", {"multipath.echoes"});
  expect_error(std::string(kMinimal) + "multipath: {model: land-mobile, echoes: 9}\n", {"multipath.echoes", "out of range"});
  expect_error(std::string(kMinimal) + "multipath: {model: land-mobile, blocked_probability: 1.2}\n",
               {"multipath.blocked_probability", "out of range"});
  expect_error(std::string(kMinimal) + "multipath: {model: ground, reflection_coefficient: 1.5}\n",
               {"multipath.reflection_coefficient"});
  expect_error(std::string(kMinimal) + "multipath: {model: ground, height_m: 3}\n", {"multipath.height_m", "unknown field"});
  expect_error(std::string(kMinimal) + "multipath: {model: ground, environment: urban}\n", {"multipath", "not both"});
}

TEST(Scenario, MissingFileIsReported) {
  EXPECT_THROW(load_scenario("/nonexistent/scenario.yaml"), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
