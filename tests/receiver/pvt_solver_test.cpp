#include "receiver/pvt_solver.hpp"

#include <gtest/gtest.h>

#include <random>

#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/satellite_signal_model.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Scene {
  NavData nav;
  std::map<int, Ephemeris> ephs;
  std::vector<PseudorangeObservation> obs;
  Eigen::Vector3d r_true, v_true;
};

/// Pseudoranges and Dopplers as the synthesizer models them (signals/satellite_signal_model)
/// for a receiver at a known place with clock bias 1e-4 s and drift 5e-7.
Scene make_scene(const Eigen::Vector3d& v_ecef, double noise_m, std::uint64_t seed) {
  Scene s;
  s.nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  const GpsTime t{2190, 525600.0};
  ReceiverInstant rx;
  rx.llh = {37.5665 * kDeg, 126.9780 * kDeg, 40.0};
  rx.r_ecef_m = wgs84::llh_to_ecef(rx.llh);
  rx.v_ecef_mps = v_ecef;
  rx.clock_bias_s = 1e-4;
  rx.clock_drift_sps = 5e-7;
  rx.t_true = t.plus_seconds(-rx.clock_bias_s);
  rx.t_rcv_rel_s = 0.0;
  s.r_true = rx.r_ecef_m;
  s.v_true = v_ecef;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int prn = 1; prn <= 32; ++prn) {
    const Ephemeris* e = s.nav.select(prn, t);
    if (!e || !e->healthy()) continue;
    const SatelliteInstant si = evaluate_satellite(*e, s.nav.iono, {true, true}, rx, 0.0);
    if (si.elevation_rad < 10 * kDeg) continue;
    s.ephs[prn] = *e;
    s.obs.push_back({prn, si.pseudorange_m + noise_m * n(rng), si.doppler_hz, 45.0});
  }
  return s;
}

TEST(PvtSolver, ExactPseudorangesGiveTheTruePositionClockAndVelocity) {
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(60.0, -80.0, 0.0)}) {
    Scene s = make_scene(v, 0.0, 1);
    ASSERT_GE(s.obs.size(), 6u);
    PvtSolver solver;
    const PvtSolution p = solver.solve(GpsTime{2190, 525600.0}, s.obs, s.ephs, s.nav.iono);
    ASSERT_TRUE(p.valid) << p.reason;
    EXPECT_LT((p.r_ecef_m - s.r_true).norm(), 1e-3);
    EXPECT_NEAR(p.clock_bias_m, gps::kSpeedOfLight_mps * 1e-4, 1e-3);
    // The Doppler model leaves out the atmosphere rates (mm/s).
    EXPECT_LT((p.v_ecef_mps - s.v_true).norm(), 0.01);
    EXPECT_NEAR(p.clock_drift_mps, gps::kSpeedOfLight_mps * 5e-7, 0.01);
    EXPECT_TRUE(p.excluded_prns.empty());
    EXPECT_GT(p.dops.pdop, 1.0);
    EXPECT_LT(p.dops.pdop, 5.0);
  }
}

TEST(PvtSolver, NoisyPseudorangesStayWithinTheirDilution) {
  Scene s = make_scene(Eigen::Vector3d::Zero(), 1.0, 7);
  PvtSolver solver;
  const PvtSolution p = solver.solve(GpsTime{2190, 525600.0}, s.obs, s.ephs, s.nav.iono);
  ASSERT_TRUE(p.valid);
  EXPECT_LT((p.r_ecef_m - s.r_true).norm(), 4.0 * p.dops.pdop);
}

TEST(PvtSolver, AFaultySatelliteIsExcluded) {
  Scene s = make_scene(Eigen::Vector3d::Zero(), 0.5, 3);
  ASSERT_GE(s.obs.size(), 7u);
  const int faulty = s.obs[2].prn;
  s.obs[2].pseudorange_m += 100.0;
  PvtSolver solver;
  const PvtSolution p = solver.solve(GpsTime{2190, 525600.0}, s.obs, s.ephs, s.nav.iono);
  ASSERT_TRUE(p.valid);
  ASSERT_EQ(p.excluded_prns.size(), 1u);
  EXPECT_EQ(p.excluded_prns[0], faulty);
  EXPECT_LT((p.r_ecef_m - s.r_true).norm(), 5.0);
}

TEST(PvtSolver, FewerThanFourSatellitesIsNoFix) {
  Scene s = make_scene(Eigen::Vector3d::Zero(), 0.0, 1);
  s.obs.resize(3);
  PvtSolver solver;
  const PvtSolution p = solver.solve(GpsTime{2190, 525600.0}, s.obs, s.ephs, s.nav.iono);
  EXPECT_FALSE(p.valid);
  EXPECT_NE(p.reason.find("fewer than 4"), std::string::npos);
}

}  // namespace
}  // namespace deepnav
