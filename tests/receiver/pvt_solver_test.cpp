#include "receiver/pvt/pvt_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <random>

#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/satellite_signal_model.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// The numbers of a list of GPS satellites.
std::vector<int> prns(const std::vector<SatelliteId>& satellites) {
  std::vector<int> out;
  for (const SatelliteId& s : satellites) out.push_back(s.prn);
  return out;
}

struct Scene {
  NavData nav;
  std::map<int, Ephemeris> ephs;
  std::vector<PseudorangeObservation> obs;
  Eigen::Vector3d r_true, v_true;
};

/// Pseudoranges and Dopplers as the synthesizer models them (signals/sim/satellite_signal_model)
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
    EXPECT_TRUE(prns(p.excluded_satellites).empty());
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
  ASSERT_EQ(prns(p.excluded_satellites).size(), 1u);
  EXPECT_EQ(prns(p.excluded_satellites)[0], faulty);
  EXPECT_LT((p.r_ecef_m - s.r_true).norm(), 5.0);
}

/// The satellites above 10 degrees at the Scene's place at 20:00 GPS time (10 of them),
/// and the receiver there at receiver time `t_rx` (clock bias 1e-4 s): a series of epochs
/// for the RAIM tests.
struct Series {
  NavData nav;
  std::map<int, Ephemeris> ephs;
  ReceiverInstant rx;
  GpsTime t0{2190, 590400.0};

  Series() {
    nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
    rx.llh = {37.5665 * kDeg, 126.9780 * kDeg, 40.0};
    rx.r_ecef_m = wgs84::llh_to_ecef(rx.llh);
    rx.clock_bias_s = 1e-4;
    for (int prn = 1; prn <= 32; ++prn) {
      const Ephemeris* e = nav.select(prn, t0);
      if (!e || !e->healthy()) continue;
      if (evaluate_satellite(*e, nav.iono, {true, true}, at(t0), 0.0).elevation_rad < 10 * kDeg) continue;
      ephs[prn] = *e;
    }
  }
  ReceiverInstant at(const GpsTime& t_rx) const {
    ReceiverInstant r = rx;
    r.t_true = t_rx.plus_seconds(-rx.clock_bias_s);
    return r;
  }
  /// Pseudoranges at `t_rx` with Gaussian errors of the solver's own weighting model
  /// (sigma^2 = 0.25 + 0.25 / sin^2 el + 3e3 10^(-C/N0 / 10) m^2 at 45 dB-Hz: 0.77 m at
  /// the zenith, 2 m at 15 deg), so that the residual test sees the statistics it assumes.
  std::vector<PseudorangeObservation> observe(const GpsTime& t_rx, std::mt19937_64& rng) const {
    std::normal_distribution<double> n(0.0, 1.0);
    std::vector<PseudorangeObservation> obs;
    for (const auto& [prn, e] : ephs) {
      const SatelliteInstant si = evaluate_satellite(e, nav.iono, {true, true}, at(t_rx), 0.0);
      const double s = std::max(std::sin(si.elevation_rad), 0.1);
      const double sigma_m = std::sqrt(0.25 + 0.25 / (s * s) + 3e3 * std::pow(10.0, -4.5));
      obs.push_back({prn, si.pseudorange_m + sigma_m * n(rng), si.doppler_hz, 45.0});
    }
    return obs;
  }
  double error_3d_m(const PvtSolution& p) const { return (p.r_ecef_m - rx.r_ecef_m).norm(); }
  double elevation_deg(int prn) const {
    return evaluate_satellite(ephs.at(prn), nav.iono, {true, true}, at(t0), 0.0).elevation_rad / kDeg;
  }
};

void add_bias(std::vector<PseudorangeObservation>& obs, int prn, double bias_m) {
  for (auto& o : obs)
    if (o.prn == prn) o.pseudorange_m += bias_m;
}

bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

TEST(PvtSolverRaim, NoFaultIsRarelyExcludedAtTheConfiguredFalseAlarmRate) {
  const Series s;
  ASSERT_GE(s.ephs.size(), 8u);
  std::mt19937_64 rng(11);
  PvtSolver solver;
  int excluded_epochs = 0, failed = 0;
  for (int k = 0; k < 200; ++k) {
    const GpsTime t = s.t0.plus_seconds(k);
    const PvtSolution p = solver.solve(t, s.observe(t, rng), s.ephs, s.nav.iono);
    ASSERT_TRUE(p.valid || p.raim == RaimStatus::failed) << p.reason;
    excluded_epochs += !prns(p.excluded_satellites).empty();
    failed += p.raim == RaimStatus::failed;
    if (p.valid) {
      EXPECT_LT(s.error_3d_m(p), 10.0) << k;
    }
  }
  // Pfa 1e-3 per test: about 0.2 false detections expected in 200 epochs.
  std::printf("no fault: %d of 200 epochs with an exclusion, %d failed\n", excluded_epochs, failed);
  EXPECT_LE(excluded_epochs, 10);  // 95 % of the epochs keep every satellite
  EXPECT_EQ(failed, 0);
}

TEST(PvtSolverRaim, AStepFaultIsExcludedAtItsFirstEpoch) {
  const Series s;
  ASSERT_GE(s.ephs.size(), 8u);
  const int faulty = std::next(s.ephs.begin(), 2)->first;
  constexpr int kStep = 50, kEpochs = 200;
  std::mt19937_64 rng(21);
  PvtSolver fde, fault_free;
  PvtConfig no_exclusion;
  no_exclusion.raim_max_exclusions = 0;
  PvtSolver detection_only(no_exclusion);
  double worst_fde_m = 0.0, worst_without_m = 0.0, sum2_fde = 0.0, sum2_without = 0.0;
  int excluded_before_step = 0, excluded_after_step = 0, other_exclusions = 0;
  for (int k = 0; k < kEpochs; ++k) {
    const GpsTime t = s.t0.plus_seconds(k);
    std::vector<PseudorangeObservation> obs = s.observe(t, rng);
    std::vector<PseudorangeObservation> good;
    std::copy_if(obs.begin(), obs.end(), std::back_inserter(good), [&](const auto& o) { return o.prn != faulty; });
    const PvtSolution reference = fault_free.solve(t, good, s.ephs, s.nav.iono);
    if (k >= kStep) add_bias(obs, faulty, 30.0);
    const PvtSolution p = fde.solve(t, obs, s.ephs, s.nav.iono);
    const PvtSolution q = detection_only.solve(t, obs, s.ephs, s.nav.iono);
    if (k < kStep) {
      excluded_before_step += !prns(p.excluded_satellites).empty();
      continue;
    }
    ASSERT_TRUE(p.valid) << k << ": " << p.reason;
    if (k == kStep) {  // per-epoch RAIM: at once
      EXPECT_EQ(p.raim, RaimStatus::excluded);
      EXPECT_EQ(prns(p.excluded_satellites), std::vector<int>{faulty});
    }
    excluded_after_step += contains(prns(p.excluded_satellites), faulty);
    other_exclusions +=
        static_cast<int>(prns(p.excluded_satellites).size()) - contains(prns(p.excluded_satellites), faulty);
    EXPECT_FALSE(contains(prns(p.used_satellites), faulty));
    // Excluding the one faulty satellite leaves exactly the fault-free fix of the others.
    if (prns(p.excluded_satellites).size() == 1) {
      EXPECT_LT((p.r_ecef_m - reference.r_ecef_m).norm(), 1e-3) << k;
    }
    worst_fde_m = std::max(worst_fde_m, s.error_3d_m(p));
    sum2_fde += std::pow(s.error_3d_m(p), 2);
    // Without exclusion the fault is detected and the fix withheld; its position shows
    // what would have been published.
    EXPECT_FALSE(q.valid);
    EXPECT_EQ(q.raim, RaimStatus::failed);
    EXPECT_NE(q.reason.find("RAIM"), std::string::npos) << q.reason;
    worst_without_m = std::max(worst_without_m, s.error_3d_m(q));
    sum2_without += std::pow(s.error_3d_m(q), 2);
  }
  const double n = kEpochs - kStep;
  const double rms_fde_m = std::sqrt(sum2_fde / n), rms_without_m = std::sqrt(sum2_without / n);
  std::printf(
      "30 m step on PRN %d (%.0f deg) from epoch %d: excluded at %d of %.0f epochs (%d other exclusions; %d "
      "epochs with an exclusion before the step); 3-D error RMS/max %.2f/%.2f m with FDE, %.2f/%.2f m without\n",
      faulty, s.elevation_deg(faulty), kStep, excluded_after_step, n, other_exclusions, excluded_before_step, rms_fde_m,
      worst_fde_m, rms_without_m, worst_without_m);
  EXPECT_EQ(excluded_after_step, kEpochs - kStep);
  EXPECT_LE(excluded_before_step, 2);
  // The noise is up to 2 m (1 sigma) on low satellites with a PDOP near 2: metres.
  EXPECT_LT(rms_fde_m, 3.0);
  EXPECT_LT(worst_fde_m, 8.0);
  EXPECT_GT(rms_without_m, 2.0 * rms_fde_m);
}

TEST(PvtSolverRaim, TwoFaultsAreBothExcluded) {
  const Series s;
  ASSERT_GE(s.ephs.size(), 9u);
  const int a = std::next(s.ephs.begin(), 1)->first, b = std::next(s.ephs.begin(), 5)->first;
  std::mt19937_64 rng(31);
  PvtSolver solver, fault_free;
  int both = 0;
  double worst_m = 0.0, sum2 = 0.0;
  for (int k = 0; k < 100; ++k) {
    const GpsTime t = s.t0.plus_seconds(k);
    std::vector<PseudorangeObservation> obs = s.observe(t, rng);
    // The fix of the eight good satellites alone: what FDE should arrive at.
    std::vector<PseudorangeObservation> good;
    std::copy_if(obs.begin(), obs.end(), std::back_inserter(good),
                 [&](const auto& o) { return o.prn != a && o.prn != b; });
    const PvtSolution reference = fault_free.solve(t, good, s.ephs, s.nav.iono);
    add_bias(obs, a, 30.0);
    add_bias(obs, b, -40.0);
    const PvtSolution p = solver.solve(t, obs, s.ephs, s.nav.iono);
    ASSERT_TRUE(p.valid) << k << ": " << p.reason;
    EXPECT_EQ(p.raim, RaimStatus::excluded);
    EXPECT_EQ(prns(p.excluded_satellites).size(), 2u) << k;
    both += contains(prns(p.excluded_satellites), a) && contains(prns(p.excluded_satellites), b);
    EXPECT_LT((p.r_ecef_m - reference.r_ecef_m).norm(), 1e-3) << k;
    worst_m = std::max(worst_m, s.error_3d_m(p));
    sum2 += std::pow(s.error_3d_m(p), 2);
  }
  std::printf(
      "faults on PRN %d (+30 m) and %d (-40 m): both excluded at %d of 100 epochs, 3-D error RMS/max "
      "%.2f/%.2f m\n",
      a, b, both, std::sqrt(sum2 / 100), worst_m);
  EXPECT_EQ(both, 100);
  EXPECT_LT(std::sqrt(sum2 / 100), 4.0);
}

TEST(PvtSolverRaim, AFaultThatCannotBeExcludedWithholdsTheFix) {
  const Series s;
  std::mt19937_64 rng(41);
  std::vector<PseudorangeObservation> obs = s.observe(s.t0, rng);
  ASSERT_GE(obs.size(), 5u);
  // Five satellites: the fault is detected, but excluding one would leave nothing to test.
  obs.resize(5);
  add_bias(obs, obs[1].prn, 80.0);
  PvtSolver solver;
  const PvtSolution p = solver.solve(s.t0, obs, s.ephs, s.nav.iono);
  EXPECT_FALSE(p.valid);
  EXPECT_EQ(p.raim, RaimStatus::failed);
  EXPECT_TRUE(prns(p.excluded_satellites).empty());
  EXPECT_NE(p.reason.find("RAIM: fault detected"), std::string::npos) << p.reason;
  EXPECT_NE(p.reason.find("too few satellites"), std::string::npos) << p.reason;
  EXPECT_GT(p.raim_statistic, p.raim_threshold);
  // Four satellites: no redundancy, nothing to test; the fix is published untested.
  obs.resize(4);
  const PvtSolution q = solver.solve(s.t0, obs, s.ephs, s.nav.iono);
  EXPECT_TRUE(q.valid) << q.reason;
  EXPECT_EQ(q.raim, RaimStatus::unavailable);
}

TEST(PvtSolverAtmosphere, TroposphereNoneOnPseudorangesWithoutTroposphereGivesAnUnbiasedHeight) {
  const Series s;
  const GpsTime t = s.t0;
  std::vector<PseudorangeObservation> obs;
  for (const auto& [prn, e] : s.ephs) {
    const SatelliteInstant si = evaluate_satellite(e, s.nav.iono, {true, false}, s.at(t), 0.0);
    obs.push_back({prn, si.pseudorange_m, si.doppler_hz, 45.0});
  }
  PvtSolver matched(PvtConfig{}, AtmosphereModels{IonosphereModel::klobuchar, TroposphereModel::none});
  const PvtSolution p = matched.solve(t, obs, s.ephs, s.nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_NEAR(p.llh.height_m, s.rx.llh.height_m, 1e-3);
  EXPECT_LT(s.error_3d_m(p), 1e-3);
  // The default model takes out a delay that is not there: the height moves by metres.
  PvtSolver mismatched;
  const PvtSolution q = mismatched.solve(t, obs, s.ephs, s.nav.iono);
  ASSERT_TRUE(q.valid) << q.reason;
  std::printf("height error without troposphere in the signal: %.4f m (model none), %.2f m (saastamoinen)\n",
              p.llh.height_m - s.rx.llh.height_m, q.llh.height_m - s.rx.llh.height_m);
  EXPECT_GT(std::abs(q.llh.height_m - s.rx.llh.height_m), 3.0);
}

TEST(PvtSolverAtmosphere, IonosphereNoneIgnoresValidBroadcastParameters) {
  const Series s;
  ASSERT_TRUE(s.nav.iono.valid);
  std::vector<PseudorangeObservation> obs;
  for (const auto& [prn, e] : s.ephs) {
    const SatelliteInstant si = evaluate_satellite(e, s.nav.iono, {false, true}, s.at(s.t0), 0.0);
    obs.push_back({prn, si.pseudorange_m, si.doppler_hz, 45.0});
  }
  PvtSolver solver(PvtConfig{}, AtmosphereModels{IonosphereModel::none, TroposphereModel::saastamoinen});
  const PvtSolution p = solver.solve(s.t0, obs, s.ephs, s.nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_LT(s.error_3d_m(p), 1e-3);
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
