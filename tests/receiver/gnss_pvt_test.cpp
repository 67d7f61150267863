// Position, velocity and time from GPS and Galileo together, from geometric pseudoranges of
// real broadcast ephemerides of both systems (tests/receiver/gnss_scene.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <tuple>
#include <utility>

#include "receiver/pvt/pvt_solver.hpp"
#include "tests/receiver/gnss_scene.hpp"

namespace deepnav {
namespace {

using test::GnssScene;
using test::vacuum_solver;

constexpr double c = gps::kSpeedOfLight_mps;

const GnssScene& scene() {
  static const GnssScene s;
  return s;
}

bool contains(const std::vector<SatelliteId>& v, const SatelliteId& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(GnssPvt, TheSceneHasBothSystemsInView) {
  EXPECT_GE(scene().gps.size(), 6u);
  EXPECT_GE(scene().galileo.size(), 5u);
}

TEST(GnssPvt, ExactRangesOfBothSystemsGiveTruePositionClockOffsetAndVelocity) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(1);
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, s.both_obs(s.t_rx, 0.0, rng), s.gps, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_EQ(p.used_count(GnssSystem::gps), static_cast<int>(s.gps.size()));
  EXPECT_EQ(p.used_count(GnssSystem::galileo), static_cast<int>(s.galileo.size()));
  EXPECT_LT((p.r_ecef_m - s.r_ecef_m).norm(), 1e-3);
  EXPECT_EQ(p.clock_system, GnssSystem::gps);
  EXPECT_NEAR(p.clock_bias_m, c * s.clock_bias_s, 1e-3);
  ASSERT_TRUE(p.system_offset_m.has_value());
  EXPECT_NEAR(*p.system_offset_m, s.galileo_offset_m, 1e-3);
  // Dopplers from +-0.5 s differences: curvature leaves mm/s.
  EXPECT_LT(p.v_ecef_mps.norm(), 0.01);
  EXPECT_NEAR(p.clock_drift_mps, c * s.clock_drift_sps, 0.01);
  EXPECT_EQ(p.raim, RaimStatus::passed);
  // A satellite's residual is keyed by its own system: E and G numbers do not collide.
  for (const auto& [prn, e] : s.galileo) EXPECT_TRUE(p.residuals_m.count({GnssSystem::galileo, prn}));
}

TEST(GnssPvt, BothSystemsFixBetterThanGpsAlone) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(11);
  // Weights that match the noise (1 m on every range), so RAIM sees what it assumes.
  PvtConfig config;
  config.range_errors.floor_m = 1.0;
  config.range_errors.elevation_m = 0.0;
  PvtSolver both = vacuum_solver(config), gps_only = vacuum_solver(config);
  double error_both = 0.0, error_gps = 0.0, pdop_both = 0.0, pdop_gps = 0.0;
  constexpr int kEpochs = 300;
  for (int k = 0; k < kEpochs; ++k) {
    const GpsTime t = s.t_rx.plus_seconds(k);
    const std::vector<PseudorangeObservation> gps = s.gps_obs(t, 1.0, rng);
    std::vector<PseudorangeObservation> all = gps;
    const std::vector<PseudorangeObservation> gal = s.galileo_obs(t, 1.0, rng);
    all.insert(all.end(), gal.begin(), gal.end());
    const PvtSolution a = both.solve(t, all, s.gps, s.galileo, s.gps_nav.iono);
    const PvtSolution g = gps_only.solve(t, gps, s.gps, s.gps_nav.iono);
    ASSERT_TRUE(a.valid && g.valid) << a.reason << " / " << g.reason;
    EXPECT_LT(a.dops.pdop, g.dops.pdop);
    EXPECT_LT(a.dops.hdop, g.dops.hdop);
    EXPECT_LT(a.dops.vdop, g.dops.vdop);
    pdop_both += a.dops.pdop / kEpochs;
    pdop_gps += g.dops.pdop / kEpochs;
    error_both += (a.r_ecef_m - s.r_ecef_m).squaredNorm();
    error_gps += (g.r_ecef_m - s.r_ecef_m).squaredNorm();
  }
  const double rms_both = std::sqrt(error_both / kEpochs), rms_gps = std::sqrt(error_gps / kEpochs);
  // The errors scale as the PDOPs do (to the sampling spread of 300 epochs).
  EXPECT_LT(rms_both, 0.9 * rms_gps) << rms_both << " m against " << rms_gps << " m";
  EXPECT_NEAR(rms_both / rms_gps, pdop_both / pdop_gps, 0.1);
  std::printf(
      "3D rms error over %d epochs, 1 m noise: %zu GPS + %zu Galileo %.2f m (PDOP %.2f), GPS %.2f m (PDOP %.2f)\n",
      kEpochs, s.gps.size(), s.galileo.size(), rms_both, pdop_both, rms_gps, pdop_gps);
}

TEST(GnssPvt, GalileoAloneFixesWithFourSatellites) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(3);
  std::vector<PseudorangeObservation> four = s.galileo_obs(s.t_rx, 0.0, rng);
  ASSERT_GE(four.size(), 4u);
  // The four highest, as a small constellation in view would give them.
  std::sort(four.begin(), four.end(), [&](const auto& a, const auto& b) {
    return s.elevation_deg(GnssScene::state(s.galileo.at(a.prn), s.t_rx).r_ecef_m) >
           s.elevation_deg(GnssScene::state(s.galileo.at(b.prn), s.t_rx).r_ecef_m);
  });
  four.resize(4);
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, four, {}, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_EQ(p.used_count(GnssSystem::galileo), 4);
  EXPECT_LT((p.r_ecef_m - s.r_ecef_m).norm(), 0.01);
  // With Galileo alone the clock is the Galileo measurements' own: GPS clock plus the offset.
  EXPECT_EQ(p.clock_system, GnssSystem::galileo);
  EXPECT_FALSE(p.system_offset_m.has_value());
  EXPECT_NEAR(p.clock_bias_m, c * s.clock_bias_s + s.galileo_offset_m, 0.01);
  EXPECT_EQ(p.raim, RaimStatus::unavailable);
}

TEST(GnssPvt, GalileoAloneWithNoiseStaysWithinItsDilution) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(5);
  PvtSolver solver = vacuum_solver();
  for (int k = 0; k < 20; ++k) {
    const GpsTime t = s.t_rx.plus_seconds(10 * k);
    const PvtSolution p = solver.solve(t, s.galileo_obs(t, 1.0, rng), {}, s.galileo, s.gps_nav.iono);
    ASSERT_TRUE(p.valid) << p.reason;
    EXPECT_LT((p.r_ecef_m - s.r_ecef_m).norm(), 4.0 * p.dops.pdop) << k;
  }
}

TEST(GnssPvt, TheInterSystemOffsetIsRecoveredFromNoisyRanges) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(9);
  PvtSolver solver = vacuum_solver();
  double sum = 0.0;
  constexpr int kEpochs = 30;
  for (int k = 0; k < kEpochs; ++k) {
    const GpsTime t = s.t_rx.plus_seconds(k);
    const PvtSolution p = solver.solve(t, s.both_obs(t, 1.0, rng), s.gps, s.galileo, s.gps_nav.iono);
    ASSERT_TRUE(p.valid && p.system_offset_m) << p.reason;
    EXPECT_NEAR(*p.system_offset_m, s.galileo_offset_m, 3.0) << k;
    sum += *p.system_offset_m;
  }
  EXPECT_NEAR(sum / kEpochs, s.galileo_offset_m, 0.5);
}

/// A 100 m fault on one satellite of `system` (the one at index 1 of that system's list).
void expect_fault_excluded(GnssSystem system, std::uint64_t seed) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(seed);
  std::vector<PseudorangeObservation> obs = s.both_obs(s.t_rx, 0.5, rng);
  const auto first = std::find_if(obs.begin(), obs.end(), [&](const auto& o) { return o.system == system; });
  ASSERT_NE(first, obs.end());
  auto& faulty = *std::next(first);
  ASSERT_EQ(faulty.system, system);
  faulty.pseudorange_m += 100.0;
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, obs, s.gps, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_EQ(p.raim, RaimStatus::excluded);
  ASSERT_EQ(p.excluded_satellites.size(), 1u);
  EXPECT_EQ(p.excluded_satellites[0], faulty.satellite());
  EXPECT_FALSE(contains(p.used_satellites, faulty.satellite()));
  EXPECT_TRUE(p.system_offset_m.has_value());
  EXPECT_LT((p.r_ecef_m - s.r_ecef_m).norm(), 5.0);
  EXPECT_LT(p.raim_statistic, p.raim_threshold);
  // Detection alone: the same fault makes the fix fail rather than publish.
  PvtConfig detect;
  detect.raim_max_exclusions = 0;
  PvtSolver detector = vacuum_solver(detect);
  const PvtSolution q = detector.solve(s.t_rx, obs, s.gps, s.galileo, s.gps_nav.iono);
  EXPECT_FALSE(q.valid);
  EXPECT_EQ(q.raim, RaimStatus::failed);
}

TEST(GnssPvt, RaimExcludesAFaultyGalileoSatellite) { expect_fault_excluded(GnssSystem::galileo, 21); }

TEST(GnssPvt, RaimExcludesAFaultyGpsSatelliteInAMixedFix) { expect_fault_excluded(GnssSystem::gps, 22); }

TEST(GnssPvt, RaimDegreesOfFreedomCountTheOffsetState) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(4);
  std::vector<PseudorangeObservation> obs = s.gps_obs(s.t_rx, 0.0, rng);
  obs.resize(4);
  std::vector<PseudorangeObservation> gal = s.galileo_obs(s.t_rx, 0.0, rng);
  gal.resize(1);
  obs.push_back(gal[0]);
  // Five satellites of two systems: five unknowns, nothing left to test.
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, obs, s.gps, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_EQ(p.raim, RaimStatus::unavailable);
  gal = s.galileo_obs(s.t_rx, 0.0, rng);
  obs.push_back(gal[1]);
  const PvtSolution q = solver.solve(s.t_rx, obs, s.gps, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(q.valid) << q.reason;
  EXPECT_EQ(q.raim, RaimStatus::passed);
  EXPECT_GT(q.raim_threshold, 0.0);
  EXPECT_LT((q.r_ecef_m - s.r_ecef_m).norm(), 0.01);
}

TEST(GnssPvt, ASystemWhollyBelowTheMaskLeavesTheOtherSystemsFix) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(8);
  std::vector<PseudorangeObservation> obs = s.gps_obs(s.t_rx, 0.0, rng);
  // The lowest Galileo satellite, and a mask just above it.
  double lowest = 90.0;
  int lowest_prn = 0;
  for (const auto& [prn, e] : s.galileo) {
    const double el = s.elevation_deg(GnssScene::state(e, s.t_rx).r_ecef_m);
    if (el < lowest) std::tie(lowest, lowest_prn) = std::pair(el, prn);
  }
  for (const auto& o : s.galileo_obs(s.t_rx, 0.0, rng))
    if (o.prn == lowest_prn) obs.push_back(o);
  PvtConfig config;
  config.elevation_mask_rad = (lowest + 0.5) * test::kSceneDeg;
  PvtSolver solver(config, AtmosphereModels{IonosphereModel::none, TroposphereModel::none});
  const PvtSolution p = solver.solve(s.t_rx, obs, s.gps, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  ASSERT_GE(p.used_count(GnssSystem::gps), 5);
  EXPECT_EQ(p.used_count(GnssSystem::galileo), 0);
  EXPECT_FALSE(p.system_offset_m.has_value());
  EXPECT_EQ(p.clock_system, GnssSystem::gps);
  EXPECT_LT((p.r_ecef_m - s.r_ecef_m).norm(), 1e-3);
  EXPECT_NEAR(p.clock_bias_m, c * s.clock_bias_s, 1e-3);
}

TEST(GnssPvt, AGalileoObservationWithoutEphemerisIsLeftOut) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(6);
  PvtSolver solver = vacuum_solver();
  // GPS ephemerides only: the Galileo rows have no satellite state, the fix is GPS's.
  const PvtSolution p = solver.solve(s.t_rx, s.both_obs(s.t_rx, 0.0, rng), s.gps, {}, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_EQ(p.used_count(GnssSystem::galileo), 0);
  EXPECT_FALSE(p.system_offset_m.has_value());
  EXPECT_LT((p.r_ecef_m - s.r_ecef_m).norm(), 1e-3);
}

}  // namespace
}  // namespace deepnav
