#include "receiver/pvt/doppler_position.hpp"

#include <gtest/gtest.h>

#include "snapshot_scene.hpp"

namespace deepnav {
namespace {

using namespace snapshot_test;

TEST(DopplerPosition, TensOfHertzGiveTensOfKilometresAnywhere) {
  // Doppler noise 15 Hz, time hint off by up to a minute: within 100 km everywhere (the
  // whole milliseconds tolerate 150 km), and within 4 of its own sigmas.
  for (const wgs84::Llh& place : test_places()) {
    SceneSpec spec;
    spec.place = place;
    const Scene s = make_scene(spec);
    for (double time_error_s : {0.0, 60.0, -60.0}) {
      const DopplerPosition p = solve_doppler_position(doppler_satellites(s), s.t_receiver.plus_seconds(time_error_s));
      ASSERT_TRUE(p.valid) << p.reason;
      const double error_m = (p.r_ecef_m - s.r_true).norm();
      EXPECT_LT(error_m, 100e3) << place.lat_rad / kDeg << " " << time_error_s;
      EXPECT_LT(error_m, 4.0 * std::sqrt(p.covariance_m2.trace()));
      EXPECT_LT(p.statistic, p.threshold);
      EXPECT_GT(p.starts, 1);
      // c * 1e-7 s/s of drift: 30 m/s, to a few m/s.
      EXPECT_NEAR(p.clock_drift_mps, gps::kSpeedOfLight_mps * spec.clock_drift_sps, 10.0);
    }
  }
}

TEST(DopplerPosition, ExactDopplersGiveMetres) {
  SceneSpec spec;
  spec.place = test_places()[2];
  spec.doppler_noise_hz = 0.0;
  const Scene s = make_scene(spec);
  const DopplerPosition p = solve_doppler_position(doppler_satellites(s), s.t_receiver);
  ASSERT_TRUE(p.valid) << p.reason;
  // The receiver clock bias (0.3 ms) is a time error the Dopplers do not model: ~1 m/s of satellite motion.
  EXPECT_LT((p.r_ecef_m - s.r_true).norm(), 100.0);
}

TEST(DopplerPosition, DopplersOfAnotherHourFitNoReceiver) {
  SceneSpec spec;
  spec.place = test_places()[0];
  const Scene s = make_scene(spec);
  const DopplerPosition p = solve_doppler_position(doppler_satellites(s), s.t_receiver.plus_seconds(3600.0));
  EXPECT_FALSE(p.valid);
  EXPECT_FALSE(p.reason.empty());
}

TEST(DopplerPosition, FourDopplersAreTooFew) {
  SceneSpec spec;
  spec.place = test_places()[0];
  const Scene s = make_scene(spec);
  auto sats = doppler_satellites(s);
  sats.resize(4);
  const DopplerPosition p = solve_doppler_position(sats, s.t_receiver);
  EXPECT_FALSE(p.valid);
  EXPECT_NE(p.reason.find("at least 5 needed"), std::string::npos);
}

}  // namespace
}  // namespace deepnav
