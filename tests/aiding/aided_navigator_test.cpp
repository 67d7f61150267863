// The closed-loop INS/GNSS filter against simulated truth: loose updates on paper 003's
// [docs/references.md] land circle, tight updates from broadcast-ephemeris satellites (including a stretch
// with only three), and an hour-long run that must keep the covariance sound.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>

#include "aiding/satellite_fault_monitor.hpp"
#include "aiding_test_fixture.hpp"
#include "ins/gps_time.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding {
namespace {

using testing::SimulatedRun;

constexpr double kDeg = M_PI / 180.0;

struct LooseOutcome {
  double horizontal_rms_m = 0.0;
  double vertical_rms_m = 0.0;
  double final_heading_error_rad = 0.0;
  bool healthy = false;
  double min_eigenvalue = 0.0;
};

/// Loose coupling at 1 Hz with noisy antenna positions and velocities; errors scored over
/// the second half of the run.
/// velocity_lag_s: the fixes' velocities are the truth that long before the fix (a Doppler
/// window's mean); tell_lag: the filter is told so.
LooseOutcome run_loose(const SimulatedRun& run, double duration_s, std::uint64_t seed, double velocity_lag_s = 0.0,
                       bool tell_lag = false) {
  AidedNavigator nav(run.perturbed_start({3.0, -2.0, 4.0}, {0.3, -0.2, 0.1}, {0.2 * kDeg, -0.2 * kDeg, 3.0 * kDeg}),
                     0.0, 0.0, testing::navigator_config(run.imu_model), InitialUncertainty{});
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  const Eigen::Vector3d pos_sigma{1.5, 1.5, 3.0}, vel_sigma{0.05, 0.05, 0.08};
  double next_fix = 1.0, sum_h2 = 0.0, sum_v2 = 0.0;
  int scored = 0;
  for (const ImuSample& s : run.imu) {
    if (s.t_s > duration_s + 1e-9) break;
    nav.propagate(s);
    if (std::abs(s.t_s - next_fix) > 1e-6) continue;
    next_fix += 1.0;
    const TrajectoryState truth = run.trajectory->at(s.t_s);
    const wgs84::Llh at = wgs84::ecef_to_llh(truth.r_ecef_m);
    const Eigen::Vector3d dr{pos_sigma(0) * n01(rng), pos_sigma(1) * n01(rng), pos_sigma(2) * n01(rng)};
    const Eigen::Vector3d dv{vel_sigma(0) * n01(rng), vel_sigma(1) * n01(rng), vel_sigma(2) * n01(rng)};
    const Eigen::Vector3d v_fix = run.trajectory->at(s.t_s - velocity_lag_s).v_ecef_mps;
    nav.update_position_velocity(truth.r_ecef_m + ned_to_ecef_vector(at, dr), v_fix + ned_to_ecef_vector(at, dv),
                                 pos_sigma, vel_sigma, 0.0,
                                 tell_lag ? std::optional<double>(-velocity_lag_s) : std::nullopt);
    if (s.t_s > duration_s / 2) {
      const Eigen::Vector3d e = testing::antenna_error_ned(nav, *run.trajectory);
      sum_h2 += e.head<2>().squaredNorm();
      sum_v2 += e(2) * e(2);
      ++scored;
    }
  }
  LooseOutcome o;
  o.horizontal_rms_m = std::sqrt(sum_h2 / scored);
  o.vertical_rms_m = std::sqrt(sum_v2 / scored);
  o.final_heading_error_rad = testing::heading_error_rad(nav, *run.trajectory);
  o.healthy = nav.healthy();
  o.min_eigenvalue = Eigen::SelfAdjointEigenSolver<StateMatrix>(nav.covariance()).eigenvalues().minCoeff();
  return o;
}

TEST(AidedNavigator, LooseCouplingOnTheLandCircleAveragesTheFixesThroughTheLeverArm) {
  const SimulatedRun run("land-circle", "tactical", 200.0, 100.0, 11);
  const LooseOutcome o = run_loose(run, 200.0, 5);
  EXPECT_TRUE(o.healthy);
  // Averaging 1 Hz fixes of 1.5 m / 3 m noise: well under the fixes' own scatter. (A
  // lever arm of 0.9 m applied with the wrong sign or frame shows up as ~1 m here.)
  EXPECT_LT(o.horizontal_rms_m, 1.2);
  EXPECT_LT(o.vertical_rms_m, 2.0);
}

TEST(AidedNavigator, LooseCouplingOnTheAircraftCircleFindsTheHeading) {
  // 4.4 m/s^2 of centripetal acceleration makes heading observable (the land circle's
  // 0.09 m/s^2 hardly does): the 3 deg start error must be removed.
  const SimulatedRun run("air-circle", "tactical", 200.0, 100.0, 14);
  const LooseOutcome o = run_loose(run, 200.0, 7);
  EXPECT_TRUE(o.healthy);
  EXPECT_LT(std::abs(o.final_heading_error_rad), 0.2 * kDeg);
  EXPECT_LT(o.horizontal_rms_m, 1.2);
}

TEST(AidedNavigator, LooseVelocityIsComparedAtTheDopplersOwnTime) {
  // A receiver's Doppler velocity is a mean over the last 100 ms, about 55 ms old at the
  // fix: in a 4.4 m/s^2 turn that is 0.24 m/s off the velocity at the fix, which a filter
  // comparing it with the current INS velocity turns into metres of position error.
  const SimulatedRun run("air-circle", "tactical", 200.0, 100.0, 14);
  const LooseOutcome told = run_loose(run, 200.0, 7, 0.055, true);
  const LooseOutcome untold = run_loose(run, 200.0, 7, 0.055, false);
  EXPECT_TRUE(told.healthy);
  EXPECT_LT(told.horizontal_rms_m, 1.2);
  EXPECT_LT(told.horizontal_rms_m, 0.6 * untold.horizontal_rms_m)
      << told.horizontal_rms_m << " vs " << untold.horizontal_rms_m;
}

TEST(AidedNavigator, AnHourOfLooseUpdatesKeepsTheCovarianceSymmetricPositiveDefinite) {
  const SimulatedRun run("static", "industrial-mems", 3600.0, 10.0, 12);
  const LooseOutcome o = run_loose(run, 3600.0, 6);
  EXPECT_TRUE(o.healthy);
  EXPECT_GT(o.min_eigenvalue, 0.0);
  EXPECT_LT(o.horizontal_rms_m, 1.0);
  EXPECT_LT(o.vertical_rms_m, 2.0);
}

/// Tight coupling with the satellites of data/brdc0010.22n above 10 deg at 02:00 GPS time.
struct TightRun {
  NavData nav_data = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  GpsTime t0 = gps_time_from_calendar(CalendarTime{2022, 1, 1, 2, 0, 0.0});
  double clock_bias0_m = 3000.0, clock_drift_mps = 90.0;  // 10 us and 0.3 ppm
  bool signal_has_ionosphere = true;   ///< false: the measurements lack the delay the navigator models
  bool signal_has_troposphere = true;  ///< false: likewise for the troposphere

  /// Satellite `e` measured from the truth at t_s (pseudorange and rate noise in sigmas
  /// given, plus `pseudorange_fault_m`), predicted from the navigator's own state.
  RangeMeasurement measure(const Ephemeris& e, const AidedNavigator& nav, const TrajectoryState& truth, double t_s,
                           double pseudorange_sigma_m, double rate_sigma_mps, std::mt19937_64& rng,
                           double pseudorange_fault_m = 0.0) const {
    std::normal_distribution<double> n01;
    const GpsTime t_rx = t0.plus_seconds(t_s);
    const double b = clock_bias0_m + clock_drift_mps * t_s;
    RangePrediction actual = predict_range(e, t_rx, b, truth.r_ecef_m, truth.v_ecef_mps,
                                           signal_has_ionosphere ? nav_data.iono : IonoParameters{});
    if (!signal_has_troposphere) {  // what is left of the delay and the carrier's rate is the ionosphere's
      actual.atmosphere_m = actual.ionosphere_m;
      actual.carrier_atmosphere_rate_mps = -actual.ionosphere_rate_mps;
    }
    RangeMeasurement m;
    m.satellite = {GnssSystem::gps, e.prn};
    m.geometry = predict_range(e, t_rx, nav.clock_bias_m(), nav.antenna_ecef_m(), nav.antenna_velocity_ecef_mps(),
                               nav_data.iono);
    m.pseudorange_m = actual.pseudorange_m(b) + pseudorange_sigma_m * n01(rng) + pseudorange_fault_m;
    m.pseudorange_sigma_m = pseudorange_sigma_m;
    m.rate_mps = actual.pseudorange_rate_mps(truth.v_ecef_mps, clock_drift_mps) + rate_sigma_mps * n01(rng);
    m.rate_sigma_mps = rate_sigma_mps;
    return m;
  }

  std::vector<const Ephemeris*> visible(const Eigen::Vector3d& r_ecef) const {
    std::vector<const Ephemeris*> out;
    for (int prn = 1; prn <= 32; ++prn) {
      const Ephemeris* e = nav_data.select(prn, t0);
      if (!e) continue;
      if (predict_range(*e, t0, 0.0, r_ecef, Eigen::Vector3d::Zero(), nav_data.iono).elevation_rad > 10.0 * kDeg)
        out.push_back(e);
    }
    return out;
  }
};

TEST(AidedNavigator, TightCouplingKeepsEstimatingWithThreeSatellites) {
  const SimulatedRun run("land-circle", "tactical", 180.0, 100.0, 13);
  TightRun tr;
  const auto sats = tr.visible(run.trajectory->at(0.0).r_ecef_m);
  ASSERT_GE(sats.size(), 6u);
  AidedNavigator nav(run.perturbed_start({4.0, 3.0, -5.0}, {0.2, 0.2, -0.1}, {0.1 * kDeg, 0.1 * kDeg, 2.0 * kDeg}),
                     tr.clock_bias0_m + 20.0, tr.clock_drift_mps - 0.5, testing::navigator_config(run.imu_model),
                     InitialUncertainty{});
  std::mt19937_64 rng(21);
  double next = 1.0, worst_three_m = 0.0;
  for (const ImuSample& s : run.imu) {
    nav.propagate(s);
    if (std::abs(s.t_s - next) > 1e-6) continue;
    next += 1.0;
    const TrajectoryState truth = run.trajectory->at(s.t_s);
    const std::size_t used = s.t_s < 120.0 ? sats.size() : 3;  // only three for the last minute
    std::vector<RangeMeasurement> ms;
    for (std::size_t k = 0; k < used; ++k) ms.push_back(tr.measure(*sats[k], nav, truth, s.t_s, 3.0, 0.05, rng));
    nav.update_ranges(ms);
    const double h = testing::antenna_error_ned(nav, *run.trajectory).head<2>().norm();
    if (s.t_s >= 120.0) worst_three_m = std::max(worst_three_m, h);
  }
  EXPECT_TRUE(nav.healthy());
  EXPECT_NEAR(nav.clock_drift_mps(), tr.clock_drift_mps, 0.1);
  // With three satellites the filter still runs on: the error grows only slowly.
  EXPECT_LT(worst_three_m, 5.0);
}

/// Tight coupling on the land circle from measurements without ionosphere, the navigator
/// predicting with Klobuchar (the mismatch a generator without ionosphere gives): the mean
/// down error over the last minute and the estimated scale error of the model at the end.
struct IonosphereMismatchOutcome {
  double mean_down_m = 0.0;
  double scale_residual = 0.0;
  bool healthy = false;
};

IonosphereMismatchOutcome run_ionosphere_mismatch(bool ionosphere_state) {
  const SimulatedRun run("land-circle", "tactical", 180.0, 100.0, 13);
  TightRun tr;
  tr.signal_has_ionosphere = false;
  const auto sats = tr.visible(run.trajectory->at(0.0).r_ecef_m);
  NavigatorConfig cfg = testing::navigator_config(run.imu_model);
  cfg.ionosphere.enabled = ionosphere_state;
  AidedNavigator nav(run.perturbed_start({2.0, -2.0, 3.0}, {0.1, 0.1, -0.1}, {0.1 * kDeg, 0.1 * kDeg, 1.0 * kDeg}),
                     tr.clock_bias0_m, tr.clock_drift_mps, cfg, InitialUncertainty{});
  std::mt19937_64 rng(41);
  double next = 1.0, sum_down = 0.0;
  int scored = 0;
  for (const ImuSample& s : run.imu) {
    nav.propagate(s);
    if (std::abs(s.t_s - next) > 1e-6) continue;
    next += 1.0;
    const TrajectoryState truth = run.trajectory->at(s.t_s);
    std::vector<RangeMeasurement> ms;
    for (const Ephemeris* e : sats) ms.push_back(tr.measure(*e, nav, truth, s.t_s, 1.0, 0.02, rng));
    nav.update_ranges(ms);
    if (s.t_s >= 120.0) {
      sum_down += testing::antenna_error_ned(nav, *run.trajectory)(2);
      ++scored;
    }
  }
  return {sum_down / scored, nav.ionosphere_scale_residual(), nav.healthy()};
}

TEST(AidedNavigator, IonosphereScaleStateTakesTheModelsDelayTheSignalLacks) {
  const IonosphereMismatchOutcome without = run_ionosphere_mismatch(false), with = run_ionosphere_mismatch(true);
  ASSERT_TRUE(without.healthy);
  ASSERT_TRUE(with.healthy);
  // Off, the state never moves and the model's elevation pattern goes into the height.
  EXPECT_EQ(without.scale_residual, 0.0);
  EXPECT_GT(std::abs(without.mean_down_m), 2.0);
  // On, it finds that the signal has none of the model's delay (scale -1) and the height
  // comes back.
  EXPECT_NEAR(with.scale_residual, -1.0, 0.3);
  EXPECT_LT(std::abs(with.mean_down_m), 0.25 * std::abs(without.mean_down_m));
}

TEST(AidedNavigator, TroposphereStateTakenMidRunStartsFromTheFitAndUndoesTheLean) {
  // Tight coupling without troposphere in the measurements, the navigator modelling it: for
  // a minute the 17 states take the model's error into the position (most into the height,
  // some across); then the zenith state is taken from a fit 10 % short of the truth.
  const SimulatedRun run("land-circle", "tactical", 150.0, 100.0, 13);
  TightRun tr;
  tr.signal_has_troposphere = false;
  const auto sats = tr.visible(run.trajectory->at(0.0).r_ecef_m);
  const RangePrediction look = predict_range(*sats.front(), tr.t0, 0.0, run.trajectory->at(0.0).r_ecef_m,
                                             Eigen::Vector3d::Zero(), tr.nav_data.iono);
  const double model_zenith_m = (look.atmosphere_m - look.ionosphere_m) / look.troposphere_mapping;
  ASSERT_GT(model_zenith_m, 2.0);
  AidedNavigator nav(run.perturbed_start({2.0, -2.0, 3.0}, {0.1, 0.1, -0.1}, {0.1 * kDeg, 0.1 * kDeg, 1.0 * kDeg}),
                     tr.clock_bias0_m, tr.clock_drift_mps, testing::navigator_config(run.imu_model),
                     InitialUncertainty{});
  std::mt19937_64 rng(43);
  constexpr double kTakenAt = 60.0;
  double next = 1.0;
  Eigen::Vector3d sum_before = Eigen::Vector3d::Zero(), sum_after = Eigen::Vector3d::Zero();
  int before = 0, after = 0;
  for (const ImuSample& s : run.imu) {
    nav.propagate(s);
    if (std::abs(s.t_s - next) > 1e-6) continue;
    next += 1.0;
    if (s.t_s == kTakenAt) {
      const double room_m = nav.enable_troposphere_state(-0.9 * model_zenith_m, 0.5);
      EXPECT_DOUBLE_EQ(nav.troposphere_residual_m(), -0.9 * model_zenith_m) << "starts from the fit";
      EXPECT_NEAR(room_m, 2.7 * model_zenith_m, 1e-9) << "room for a few times the zenith error in height";
    }
    const TrajectoryState truth = run.trajectory->at(s.t_s);
    std::vector<RangeMeasurement> ms;
    for (const Ephemeris* e : sats) ms.push_back(tr.measure(*e, nav, truth, s.t_s, 0.5, 0.02, rng));
    nav.update_ranges(ms);
    const Eigen::Vector3d err = testing::antenna_error_ned(nav, *run.trajectory);
    if (s.t_s >= kTakenAt - 30.0 && s.t_s < kTakenAt) {
      sum_before += err;
      ++before;
    } else if (s.t_s >= kTakenAt + 10.0) {
      sum_after += err;
      ++after;
    }
  }
  ASSERT_TRUE(nav.healthy());
  const Eigen::Vector3d mean_before = sum_before / before, mean_after = sum_after / after;
  std::printf("mean error before n %+.3f e %+.3f d %+.3f, after n %+.3f e %+.3f d %+.3f, state %.3f of %.3f\n",
              mean_before(0), mean_before(1), mean_before(2), mean_after(0), mean_after(1), mean_after(2),
              nav.troposphere_residual_m(), -model_zenith_m);
  EXPECT_GT(std::abs(mean_before(2)), 2.0 * model_zenith_m) << "the model's error is in the height";
  // Ten seconds on, the height is back and the lean gone; the state finds the rest.
  EXPECT_LT(std::abs(mean_after(2)), 0.5);
  EXPECT_LT(mean_after.head<2>().norm(), 0.5 * mean_before.head<2>().norm());
  EXPECT_NEAR(nav.troposphere_residual_m(), -model_zenith_m, 0.3);
}

/// Tight coupling on the land circle with a pseudorange step of `step_m` on the first
/// satellite from t = 60 s, the rows fed through the per-satellite fault monitor as the
/// aided receiver does (or not): when the monitor excluded it, and the worst horizontal
/// error after the step.
struct StepOutcome {
  double excluded_after_s = -1.0;
  double worst_h_m = 0.0;
  bool healthy = false;
};

StepOutcome run_tight_step(double step_m, bool monitor) {
  const SimulatedRun run("land-circle", "tactical", 120.0, 100.0, 13);
  TightRun tr;
  const auto sats = tr.visible(run.trajectory->at(0.0).r_ecef_m);
  AidedNavigator nav(run.perturbed_start({2.0, -2.0, 3.0}, {0.1, 0.1, -0.1}, {0.1 * kDeg, 0.1 * kDeg, 1.0 * kDeg}),
                     tr.clock_bias0_m, tr.clock_drift_mps, testing::navigator_config(run.imu_model),
                     InitialUncertainty{});
  SatelliteFaultMonitor faults;
  std::mt19937_64 rng(31);
  StepOutcome out;
  double next = 1.0;
  const int faulty = sats.front()->prn;
  for (const ImuSample& s : run.imu) {
    nav.propagate(s);
    if (std::abs(s.t_s - next) > 1e-6) continue;
    next += 1.0;
    const TrajectoryState truth = run.trajectory->at(s.t_s);
    std::vector<RangeMeasurement> used, watched;
    for (const Ephemeris* e : sats) {
      const double fault_m = e->prn == faulty && s.t_s >= 60.0 ? step_m : 0.0;
      (monitor && faults.excluded({GnssSystem::gps, e->prn}) ? watched : used)
          .push_back(tr.measure(*e, nav, truth, s.t_s, 1.0, 0.05, rng, fault_m));
    }
    std::vector<SatelliteInnovation> rows;
    nav.update_ranges(used, monitor ? &rows : nullptr, watched);
    faults.add(s.t_s, rows);
    if (out.excluded_after_s < 0.0 && faults.excluded({GnssSystem::gps, faulty})) out.excluded_after_s = s.t_s - 60.0;
    if (s.t_s >= 60.0)
      out.worst_h_m = std::max(out.worst_h_m, testing::antenna_error_ned(nav, *run.trajectory).head<2>().norm());
  }
  out.healthy = nav.healthy();
  return out;
}

TEST(AidedNavigator, TightCouplingExcludesASatelliteWithAStepAndStaysWithinBounds) {
  // 30 m on a 1 m row: the gate turns each row away; the monitor takes the satellite out.
  const StepOutcome big = run_tight_step(30.0, true);
  EXPECT_TRUE(big.healthy);
  EXPECT_GE(big.excluded_after_s, 0.0);
  EXPECT_LE(big.excluded_after_s, 3.0) << "excluded within a few epochs";
  EXPECT_LT(big.worst_h_m, 2.0);
  // 4.5 m (4.5 sigma): under the gate, every row would pull the solution.
  const StepOutcome small = run_tight_step(4.5, true), unwatched = run_tight_step(4.5, false);
  EXPECT_GE(small.excluded_after_s, 0.0);
  EXPECT_LE(small.excluded_after_s, 10.0);
  EXPECT_LT(small.worst_h_m, unwatched.worst_h_m) << "excluding it beats letting it through the gate";
}

}  // namespace
}  // namespace deepnav::aiding
