#include "receiver/pvt/doppler_velocity.hpp"

#include <gtest/gtest.h>

#include "snapshot_scene.hpp"

namespace deepnav {
namespace {

using namespace snapshot_test;

std::map<int, double> dopplers_of(const Scene& s) {
  std::map<int, double> out;
  for (const SnapshotMeasurement& m : s.measurements) out[m.prn] = *m.doppler_hz;
  return out;
}

TEST(DopplerVelocity, StandingStillWithTheClockDriftFromExactDopplers) {
  SceneSpec spec;
  spec.place = test_places()[0];
  spec.doppler_noise_hz = 0.0;
  const Scene s = make_scene(spec);
  const auto v = velocity_from_dopplers(dopplers_of(s), s.ephemerides, s.spec.t_true, s.r_true,
                                        broadcast_navigation().iono, AtmosphereModels{});
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->satellites, static_cast<int>(s.measurements.size()));
  EXPECT_LT(v->v_ecef_mps.norm(), 0.05);
  EXPECT_NEAR(v->clock_drift_mps, gps::kSpeedOfLight_mps * spec.clock_drift_sps, 0.05);
}

TEST(DopplerVelocity, NoiseOfFifteenHertzGivesMetresPerSecondAtMost) {
  for (const wgs84::Llh& place : test_places()) {
    SceneSpec spec;
    spec.place = place;
    spec.seed = 7;
    const Scene s = make_scene(spec);
    const auto v = velocity_from_dopplers(dopplers_of(s), s.ephemerides, s.spec.t_true, s.r_true,
                                          broadcast_navigation().iono, AtmosphereModels{});
    ASSERT_TRUE(v.has_value());
    // 15 Hz is 2.9 m/s on each range rate; over 8-11 satellites the velocity's error
    // stays within a few of those.
    EXPECT_LT(v->v_ecef_mps.norm(), 10.0);
  }
}

TEST(DopplerVelocity, SatellitesWithoutEphemerisLeftOutAndTooFewRefused) {
  SceneSpec spec;
  spec.place = test_places()[1];
  spec.doppler_noise_hz = 0.0;
  const Scene s = make_scene(spec);
  const std::map<int, double> dopplers = dopplers_of(s);
  // Without the first satellite's ephemeris: left out, the rest still fix the velocity.
  std::map<int, Ephemeris> fewer = s.ephemerides;
  fewer.erase(fewer.begin());
  const auto v =
      velocity_from_dopplers(dopplers, fewer, s.spec.t_true, s.r_true, broadcast_navigation().iono, AtmosphereModels{});
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->satellites, static_cast<int>(fewer.size()));
  EXPECT_LT(v->v_ecef_mps.norm(), 0.05);
  // Three satellites cannot fix four unknowns.
  while (fewer.size() > 3) fewer.erase(fewer.begin());
  EXPECT_FALSE(
      velocity_from_dopplers(dopplers, fewer, s.spec.t_true, s.r_true, broadcast_navigation().iono, AtmosphereModels{})
          .has_value());
}

}  // namespace
}  // namespace deepnav
