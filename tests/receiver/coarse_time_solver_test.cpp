#include "receiver/pvt/coarse_time_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "snapshot_scene.hpp"

namespace deepnav {
namespace {

using namespace snapshot_test;

/// What every fix of a scene must get right, to within its noise (3 m of code noise).
constexpr double kMaxError_m = 25.0;

CoarseTimeFix solve(const Scene& s, double time_error_s, std::optional<Eigen::Vector3d> position_hint,
                    bool with_dopplers = true, const CoarseTimeConfig& config = {}) {
  std::vector<SnapshotMeasurement> measurements = s.measurements;
  if (!with_dopplers)
    for (auto& m : measurements) m.doppler_hz.reset();
  const CoarseTimeSolver solver(config);
  return solver.solve(measurements, s.ephemerides, broadcast_navigation().iono,
                      {s.t_receiver.plus_seconds(time_error_s), position_hint});
}

/// The checks of a fix against the scene's truth.
void expect_true_fix(const CoarseTimeFix& fix, const Scene& s, double time_error_s) {
  ASSERT_TRUE(fix.valid) << fix.reason;
  EXPECT_LT((fix.r_ecef_m - s.r_true).norm(), kMaxError_m);
  EXPECT_EQ(fix.suspect, SuspectHint::none);
  EXPECT_TRUE(fix.reason.empty());
  // The hint was the receiver clock's reading plus the time error; the correction takes
  // it to the true time (to milliseconds: what the range rates resolve).
  EXPECT_NEAR(fix.coarse_time_correction_s, -(s.spec.clock_bias_s + time_error_s), 0.02);
  EXPECT_NEAR(fix.receive_time.seconds_since(s.spec.t_true), 0.0, 0.02);
  // The clock bias, modulo one code period, to the precision of the range fit.
  const double clock_error_m =
      std::remainder(fix.clock_bias_m - gps::kSpeedOfLight_mps * s.spec.clock_bias_s, kCodePeriodRange_m);
  EXPECT_LT(std::abs(clock_error_m), 3.0 * kMaxError_m);
  EXPECT_TRUE(fix.quality.passed);
  EXPECT_LE(fix.quality.chi_square, fix.quality.chi_square_threshold);
  EXPECT_EQ(fix.quality.degrees_of_freedom, static_cast<int>(fix.used_prns.size()) - 5);
  ASSERT_TRUE(fix.clock_drift_mps.has_value());
  EXPECT_NEAR(*fix.clock_drift_mps, gps::kSpeedOfLight_mps * s.spec.clock_drift_sps, 5.0);
}

Scene scene_at(std::size_t place, double sow = 525600.0, std::uint64_t seed = 1) {
  SceneSpec spec;
  spec.place = test_places()[place];
  spec.t_true = GpsTime{2190, sow};
  spec.seed = seed;
  return make_scene(spec);
}

TEST(CoarseTimeSolver, PositionHintsUpTo100kmAndTimeHintsUpToAMinuteGiveTheFix) {
  double sum_sq_m2 = 0.0, worst_m = 0.0;
  int fixes = 0;
  for (std::size_t place = 0; place < test_places().size(); ++place) {
    for (const double sow : {525600.0, 561000.0}) {
      const Scene s = scene_at(place, sow, place + 1);
      ASSERT_GE(s.measurements.size(), 7u);
      int variant = 0;
      for (const double time_error_s : {0.0, 2.0, 10.0, 60.0, -60.0}) {
        for (const double hint_off_m : {0.0, 10e3, 100e3}) {
          const double azimuth = 0.7 * ++variant;
          const CoarseTimeFix fix = solve(s, time_error_s, moved(s.r_true, hint_off_m, azimuth));
          SCOPED_TRACE(::testing::Message() << "place " << place << " sow " << sow << " time error " << time_error_s
                                            << " s, hint " << hint_off_m / 1e3 << " km");
          expect_true_fix(fix, s, time_error_s);
          EXPECT_EQ(fix.start, CoarseTimeStart::position_hint);
          const double error_m = (fix.r_ecef_m - s.r_true).norm();
          sum_sq_m2 += error_m * error_m;
          worst_m = std::max(worst_m, error_m);
          ++fixes;
        }
      }
    }
  }
  // 3 m of code noise through the five-unknown geometry (PDOP 1.5-4 here).
  EXPECT_LT(std::sqrt(sum_sq_m2 / fixes), 10.0);
  EXPECT_LT(worst_m, kMaxError_m);
}

TEST(CoarseTimeSolver, WithoutAPositionHintTheDopplersOrTheGridFindTheFix) {
  for (std::size_t place = 0; place < test_places().size(); ++place) {
    const Scene s = scene_at(place, 561000.0, 10 + place);
    for (const double time_error_s : {0.0, 10.0, -60.0}) {
      SCOPED_TRACE(::testing::Message() << "place " << place << " time error " << time_error_s << " s");
      const CoarseTimeFix from_doppler = solve(s, time_error_s, std::nullopt);
      expect_true_fix(from_doppler, s, time_error_s);
      EXPECT_EQ(from_doppler.start, CoarseTimeStart::doppler);
      const CoarseTimeFix from_grid = solve(s, time_error_s, std::nullopt, false);
      ASSERT_TRUE(from_grid.valid) << from_grid.reason;
      EXPECT_EQ(from_grid.start, CoarseTimeStart::grid);
      EXPECT_LT((from_grid.r_ecef_m - s.r_true).norm(), kMaxError_m);
      EXPECT_GT(from_grid.quality.candidates, 100);  // the whole visible region was searched
      EXPECT_FALSE(from_grid.clock_drift_mps.has_value());
    }
  }
}

TEST(CoarseTimeSolver, ATimeHintHoursOffIsRefusedAndMeasured) {
  for (const std::size_t place : {0u, 3u}) {
    const Scene s = scene_at(place);
    for (const double time_error_s : {3600.0, -7200.0, 300.0}) {
      SCOPED_TRACE(::testing::Message() << "place " << place << " time error " << time_error_s << " s");
      const CoarseTimeFix fix = solve(s, time_error_s, s.r_true);
      EXPECT_FALSE(fix.valid);
      EXPECT_EQ(fix.suspect, SuspectHint::time) << fix.reason;
      ASSERT_TRUE(fix.time_hint_error_s.has_value()) << fix.reason;
      // The hint minus the true time: the time error and the receiver clock's 0.3 ms.
      EXPECT_NEAR(*fix.time_hint_error_s, time_error_s + s.spec.clock_bias_s, 0.05);
      EXPECT_NE(fix.reason.find("time hint off by"), std::string::npos) << fix.reason;
      EXPECT_FALSE(fix.position_hint_error_m.has_value());
      // Without a position hint it is refused too, and the time is what it blames.
      const CoarseTimeFix unhinted = solve(s, time_error_s, std::nullopt);
      EXPECT_FALSE(unhinted.valid);
      EXPECT_EQ(unhinted.suspect, SuspectHint::time) << unhinted.reason;
    }
  }
}

TEST(CoarseTimeSolver, APositionHintThousandsOfKmOffIsRefusedAndMeasured) {
  for (const std::size_t place : {1u, 2u, 4u}) {
    const Scene s = scene_at(place);
    for (const double hint_off_m : {1000e3, 2500e3}) {
      for (const bool with_dopplers : {true, false}) {
        SCOPED_TRACE(::testing::Message()
                     << "place " << place << " hint " << hint_off_m / 1e3 << " km, Dopplers " << with_dopplers);
        const Eigen::Vector3d hint = moved(s.r_true, hint_off_m, 2.0);
        const CoarseTimeFix fix = solve(s, 10.0, hint, with_dopplers);
        EXPECT_FALSE(fix.valid);
        EXPECT_EQ(fix.suspect, SuspectHint::position) << fix.reason;
        ASSERT_TRUE(fix.position_hint_error_m.has_value()) << fix.reason;
        EXPECT_NEAR(*fix.position_hint_error_m, (hint - s.r_true).norm(), kMaxError_m);
        EXPECT_NE(fix.reason.find("position hint off by"), std::string::npos) << fix.reason;
      }
    }
  }
}

TEST(CoarseTimeSolver, HintsBeyondTheToleranceGiveTheTrueFixOrARefusalNeverAWrongFix) {
  CoarseTimeConfig config;
  config.time_scan_s = 1800.0;  // keeps the diagnosis of each refusal short
  int fixes = 0, refusals = 0;
  for (std::size_t place = 0; place < test_places().size(); ++place) {
    const Scene s = scene_at(place, 540000.0, 20 + place);
    for (const double hint_off_m : {150e3, 250e3, 400e3}) {
      for (const double time_error_s : {-200.0, 90.0, 150.0}) {
        const CoarseTimeFix fix =
            solve(s, time_error_s, moved(s.r_true, hint_off_m, 1.3 * static_cast<double>(place)), true, config);
        SCOPED_TRACE(::testing::Message() << "place " << place << " hint " << hint_off_m / 1e3 << " km, time "
                                          << time_error_s << " s: " << fix.reason);
        if (fix.valid) {
          ++fixes;
          EXPECT_LT((fix.r_ecef_m - s.r_true).norm(), kMaxError_m);
        } else {
          ++refusals;
          EXPECT_FALSE(fix.reason.empty());
          EXPECT_NE(fix.suspect, SuspectHint::none);
        }
      }
    }
  }
  EXPECT_GT(refusals, 0);
  EXPECT_GT(fixes, 0);  // a 150 km hint with a 90 s time error is often still right
}

/// A position and time hint within the tolerances whose predicted ranges still give one
/// satellite a wrong whole millisecond (its line of sight lies along the hint's error).
struct MarginalHint {
  Eigen::Vector3d position;
  double time_error_s = 0.0;
  int prn = 0;
  int wrong_by = 0;
};

std::optional<MarginalHint> marginal_hint(const Scene& s) {
  for (const double time_error_s : {60.0, -60.0}) {
    const GpsTime t_hint = s.t_receiver.plus_seconds(time_error_s);
    const auto sats = fit_satellites(s, t_hint);
    CoarseTimeContext context;
    context.t_hint = t_hint;
    context.iono = broadcast_navigation().iono;
    CoarseTimeState truth;
    truth.r_ecef_m = s.r_true;
    truth.time_correction_s = -(s.spec.clock_bias_s + time_error_s);
    const WholeMilliseconds right = resolve_whole_milliseconds(sats, context, truth);
    for (double distance_m = 80e3; distance_m <= 140e3; distance_m += 10e3) {
      for (double azimuth = 0.0; azimuth < 2.0 * std::numbers::pi; azimuth += 10.0 * kDeg) {
        CoarseTimeState start;
        start.r_ecef_m = moved(s.r_true, distance_m, azimuth);
        const WholeMilliseconds ms = resolve_whole_milliseconds(sats, context, start);
        std::vector<std::size_t> differing;
        for (std::size_t k = 0; k < sats.size(); ++k) {
          const int d = (ms.milliseconds[k] - ms.milliseconds[0]) - (right.milliseconds[k] - right.milliseconds[0]);
          if (d != 0) differing.push_back(k);
        }
        if (differing.size() != 1 || differing[0] == 0) continue;
        const std::size_t k = differing[0];
        const int d = (ms.milliseconds[k] - ms.milliseconds[0]) - (right.milliseconds[k] - right.milliseconds[0]);
        return MarginalHint{start.r_ecef_m, time_error_s, sats[k].prn, d};
      }
    }
  }
  return std::nullopt;
}

TEST(CoarseTimeSolver, AWrongWholeMillisecondFromTheHintsIsRepaired) {
  int repaired = 0;
  for (std::size_t place = 0; place < test_places().size(); ++place) {
    const Scene s = scene_at(place, 525600.0, 30 + place);
    const std::optional<MarginalHint> hint = marginal_hint(s);
    if (!hint) continue;
    SCOPED_TRACE(::testing::Message() << "place " << place << " PRN " << hint->prn << " off by " << hint->wrong_by);
    const CoarseTimeFix fix = solve(s, hint->time_error_s, hint->position);
    expect_true_fix(fix, s, hint->time_error_s);
    EXPECT_EQ(fix.start, CoarseTimeStart::position_hint);
    EXPECT_EQ(fix.repaired_ms, (std::map<int, int>{{hint->prn, -hint->wrong_by}}));
    EXPECT_TRUE(fix.excluded_prns.empty());
    ++repaired;
  }
  EXPECT_GE(repaired, 2);
}

TEST(CoarseTimeSolver, ADetectionOfASatelliteBelowTheHorizonIsSetAsideWithoutAPositionHint) {
  // A long snapshot's non-coherent sum can report a satellite that is not in the signal:
  // one below the horizon leaves no place that sees every satellite.
  Scene s = scene_at(1, 561000.0, 40);
  const GpsTime t = s.spec.t_true;
  int below = 0;
  for (int prn = 1; prn <= gps::kMaxPrn && below == 0; ++prn) {
    const Ephemeris* eph = broadcast_navigation().select(prn, t);
    if (eph == nullptr || s.ephemerides.count(prn) > 0) continue;
    const Eigen::Vector3d d = satellite_state(*eph, t).r_ecef_m - s.r_true;
    if (d.dot(s.r_true.normalized()) < -0.5 * d.norm()) below = prn;  // 30 degrees below
  }
  ASSERT_NE(below, 0);
  s.ephemerides[below] = *broadcast_navigation().select(below, t);
  s.measurements.push_back({below, 512.25, std::nullopt, 45.0});
  const CoarseTimeFix fix = solve(s, 20.0, std::nullopt, false);
  ASSERT_TRUE(fix.valid) << fix.reason;
  EXPECT_LT((fix.r_ecef_m - s.r_true).norm(), kMaxError_m);
  EXPECT_EQ(fix.start, CoarseTimeStart::grid);
  EXPECT_NE(std::find(fix.excluded_prns.begin(), fix.excluded_prns.end(), below), fix.excluded_prns.end());
  EXPECT_EQ(std::find(fix.used_prns.begin(), fix.used_prns.end(), below), fix.used_prns.end());
}

TEST(CoarseTimeSolver, TooFewSatellitesAreRefusedWithoutBlamingAHint) {
  Scene s = scene_at(0);
  s.measurements.resize(5);
  const CoarseTimeFix fix = solve(s, 0.0, s.r_true);
  EXPECT_FALSE(fix.valid);
  EXPECT_EQ(fix.suspect, SuspectHint::none);
  EXPECT_NE(fix.reason.find("needs at least 6"), std::string::npos) << fix.reason;
  // Six without Dopplers or a position hint: too few to search the Earth.
  s = scene_at(0);
  s.measurements.resize(6);
  const CoarseTimeFix unhinted = solve(s, 0.0, std::nullopt, false);
  EXPECT_FALSE(unhinted.valid);
  EXPECT_EQ(unhinted.suspect, SuspectHint::none);
  EXPECT_NE(unhinted.reason.find("too few to search the Earth"), std::string::npos) << unhinted.reason;
}

TEST(CoarseTimeSolver, ASatelliteWithoutEphemerisIsLeftOutAndNamed) {
  Scene s = scene_at(3);
  const int missing = s.measurements[1].prn;
  s.ephemerides.erase(missing);
  const CoarseTimeFix fix = solve(s, 2.0, moved(s.r_true, 10e3, 0.0));
  expect_true_fix(fix, s, 2.0);
  EXPECT_EQ(fix.without_ephemeris, std::vector<int>{missing});
  EXPECT_EQ(fix.used_prns.size(), s.measurements.size() - 1);
  EXPECT_EQ(fix.residuals_m.size(), fix.used_prns.size());
  EXPECT_GT(fix.dops.pdop, 1.0);
  EXPECT_GT(fix.coarse_time_dop_s_per_m, 0.0);
}

TEST(CoarseTimeSolver, MalformedInputIsAnError) {
  Scene s = scene_at(0);
  s.measurements[0].code_phase_chips = 2000.0;
  EXPECT_THROW(solve(s, 0.0, s.r_true), std::invalid_argument);
  s = scene_at(0);
  EXPECT_THROW(solve(s, 0.0, Eigen::Vector3d(NAN, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(solve(s, 0.0, Eigen::Vector3d::Zero()), std::invalid_argument);
  try {
    solve(s, 0.0, 1.1 * s.r_true);  // 640 km up
    ADD_FAILURE() << "a position hint in space was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("position_ecef_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace deepnav
