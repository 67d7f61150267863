#include "receiver/hot_start.hpp"

#include <gtest/gtest.h>

#include "snapshot_scene.hpp"

namespace deepnav {
namespace {

using namespace snapshot_test;

constexpr double kFs_hz = 4.0e6;
constexpr std::int64_t kSample = 8'000'000;  // 2 s after sample 0

/// Hints whose time at kSample is the receiver clock's reading plus `time_error_s`.
HotStartHints hints_for(const Scene& s, double time_error_s, bool with_position) {
  HotStartHints h;
  h.first_sample_time = s.t_receiver.plus_seconds(time_error_s - static_cast<double>(kSample) / kFs_hz);
  if (with_position) h.position_ecef_m = moved(s.r_true, 20e3, 1.0);
  return h;
}

Scene scene(int place, std::uint64_t seed = 3) {
  SceneSpec spec;
  spec.place = test_places()[static_cast<std::size_t>(place)];
  spec.seed = seed;
  return make_scene(spec);
}

TEST(HotStart, FixesFromCodePhasesWithTheTimeHintSecondsOff) {
  for (const bool with_position : {true, false}) {
    const Scene s = scene(0);
    HotStart start(hints_for(s, 1.5, with_position), kFs_hz, AtmosphereModels{});
    const PvtSolution fix = start.solve(s.measurements, s.ephemerides, broadcast_navigation().iono, kSample);
    ASSERT_TRUE(fix.valid) << fix.reason;
    EXPECT_LT((fix.r_ecef_m - s.r_true).norm(), 25.0);
    EXPECT_NEAR(fix.t.seconds_since(s.spec.t_true), 0.0, 0.02);
    // Static scene: the Dopplers' velocity is near zero (15 Hz of noise on each).
    EXPECT_LT(fix.v_ecef_mps.norm(), 10.0);
    EXPECT_EQ(start.report().attempts, 1);
    EXPECT_EQ(start.report().fixes, 1);
    ASSERT_TRUE(start.report().first_correction_s.has_value());
    EXPECT_NEAR(*start.report().first_correction_s, -(1.5 + s.spec.clock_bias_s), 0.02);
    EXPECT_DOUBLE_EQ(*start.report().first_fix_sample_s, 2.0);
  }
}

TEST(HotStart, LaterEpochsTakeTheLastFixAsTheirHints) {
  const Scene s = scene(1);
  HotStart start(hints_for(s, 40.0, true), kFs_hz, AtmosphereModels{});
  ASSERT_TRUE(start.solve(s.measurements, s.ephemerides, broadcast_navigation().iono, kSample).valid);
  // A second later the hint is the fix's time plus a second, no longer the user's 40 s off.
  EXPECT_NEAR(start.time_hint_at(kSample + 4'000'000).seconds_since(s.spec.t_true), 1.0, 0.02);
}

TEST(HotStart, TooFewSatellitesAreNotTried) {
  const Scene s = scene(2);
  HotStart start(hints_for(s, 0.0, true), kFs_hz, AtmosphereModels{});
  const std::vector<SnapshotMeasurement> five(s.measurements.begin(), s.measurements.begin() + 5);
  const PvtSolution fix = start.solve(five, s.ephemerides, broadcast_navigation().iono, kSample);
  EXPECT_FALSE(fix.valid);
  EXPECT_NE(fix.reason.find("fewer than 6"), std::string::npos) << fix.reason;
  EXPECT_EQ(start.report().attempts, 0);
  // Measurements without an ephemeris do not count.
  std::map<int, Ephemeris> none;
  EXPECT_FALSE(start.solve(s.measurements, none, broadcast_navigation().iono, kSample).valid);
  EXPECT_EQ(start.report().attempts, 0);
}

TEST(HotStart, AWrongTimeHintIsRefusedNeverAFix) {
  const Scene s = scene(3);
  HotStart start(hints_for(s, 600.0, true), kFs_hz, AtmosphereModels{});
  const PvtSolution fix = start.solve(s.measurements, s.ephemerides, broadcast_navigation().iono, kSample);
  EXPECT_FALSE(fix.valid);
  EXPECT_EQ(fix.reason.rfind("hot start refused: ", 0), 0u) << fix.reason;
  EXPECT_NE(fix.reason.find("time hint"), std::string::npos) << fix.reason;
  EXPECT_EQ(start.report().attempts, 1);
  EXPECT_EQ(start.report().fixes, 0);
  EXPECT_FALSE(start.report().first_correction_s.has_value());
  EXPECT_FALSE(start.report().last_refusal.empty());
  // No fix: the next epoch's hint is still the user's.
  EXPECT_NEAR(start.time_hint_at(kSample).seconds_since(s.t_receiver), 600.0, 1e-6);
}

}  // namespace
}  // namespace deepnav
