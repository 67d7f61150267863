// The recording-driven navigator on a synthetic recording: observations made from a known
// trajectory (the satellites of data/brdc0010.22n above 10 deg, a drifting receiver clock,
// seeded noise) and the trajectory's simulated IMU. It starts the INS, converges, labels
// each epoch with what navigated, coasts on the IMU across missing epochs and an epoch
// with two satellites, stops the INS where the IMU log has no data, restarts a filter
// that turns its rows away, and takes each Doppler at the time the recording says it
// refers to.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "aiding/recorded_fusion.hpp"
#include "aiding_test_fixture.hpp"
#include "receiver/pvt/range_model.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding {
namespace {

using testing::SimulatedRun;

constexpr double kDeg = M_PI / 180.0;

struct RecordingSpec {
  std::string trajectory = "land-circle";
  double duration_s = 120.0;
  std::uint64_t seed = 7;
  double pseudorange_sigma_m = 1.0;
  double rate_sigma_mps = 0.02;
  /// The recorded Dopplers are the truth this long after their epoch (negative: a mean
  /// over a window before it).
  double doppler_time_offset_s = 0.0;
};

/// Observations and an IMU log of one simulated run, on the fusion axis (the first epoch
/// at 2022-01-01 02:00 GPS; 1 Hz epochs at whole seconds of trajectory time).
class SyntheticRecording {
 public:
  explicit SyntheticRecording(const RecordingSpec& spec)
      : spec_(spec),
        run_(spec.trajectory, "tactical", spec.duration_s + 1.0, 100.0, spec.seed),
        nav_(read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n")),
        t0_(gps_time_from_calendar(CalendarTime{2022, 1, 1, 2, 0, 0.0})) {
    const Eigen::Vector3d r0 = run_.trajectory->at(0.0).r_ecef_m;
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
      const Ephemeris* e = nav_.select(prn, t0_);
      if (e && predict_range(*e, t0_, 0.0, r0, Eigen::Vector3d::Zero(), nav_.iono).elevation_rad > 10.0 * kDeg)
        satellites_.push_back(e);
    }
    std::mt19937_64 rng(spec.seed + 1);
    for (int k = 0; k <= static_cast<int>(spec.duration_s); ++k) obs_.epochs.push_back(epoch(k, rng));
    obs_.report.nominal_interval_s = 1.0;
    obs_.report.approx_position_ecef_m = r0;
    imu_.nominal_interval_s = 0.01;
    imu_.samples = run_.imu;
    for (ImuSample& s : imu_.samples) s.t_s += t0_.sow;  // onto the fusion axis: seconds of week
  }

  RecordedFusionConfig config(NavMode mode) const {
    RecordedFusionConfig c;
    c.mode = mode;
    c.coupling.imu = run_.imu_model;
    c.coupling.lever_arm_imu_to_antenna_b_m = -testing::kImuFromAntenna_b;
    c.doppler_sigma_mps = 0.05;
    c.carrier_smoothing = false;  // no carrier phase recorded
    return c;
  }

  /// Trajectory time of an epoch.
  double seconds_of(const GpsTime& t) const { return t.seconds_since(t0_); }
  const Trajectory& trajectory() const { return *run_.trajectory; }
  ObservationFile& observations() { return obs_; }
  const NavData& navigation() const { return nav_; }
  const ImuLog& imu() const { return imu_; }
  /// Drops the IMU samples after `from_s` and before `to_s` (trajectory time; to_s past the
  /// end: the log ends at from_s), listing the gap as the log readers do.
  void cut_imu(double from_s, double to_s) {
    std::vector<ImuSample> kept;
    for (const ImuSample& s : imu_.samples)
      if (s.t_s - t0_.sow <= from_s + 1e-9 || s.t_s - t0_.sow >= to_s - 1e-9) kept.push_back(s);
    imu_.samples = kept;
    if (to_s <= spec_.duration_s) imu_.gaps.push_back({1, t0_.sow + from_s, t0_.sow + to_s});
  }
  std::size_t satellites() const { return satellites_.size(); }

 private:
  static constexpr double kClockBias0_m = 3000.0, kClockDrift_mps = 90.0;

  ObservationEpoch epoch(int k, std::mt19937_64& rng) const {
    std::normal_distribution<double> n01;
    const double t_s = k;
    ObservationEpoch e;
    e.t = t0_.plus_seconds(t_s);
    const TrajectoryState at = run_.trajectory->at(t_s);
    const double t_doppler_s = t_s + spec_.doppler_time_offset_s;
    const TrajectoryState at_doppler = run_.trajectory->at(t_doppler_s);
    for (const Ephemeris* s : satellites_) {
      const double bias_m = kClockBias0_m + kClockDrift_mps * t_s;
      const RangePrediction code = predict_range(*s, e.t, bias_m, at.r_ecef_m, at.v_ecef_mps, nav_.iono);
      const RangePrediction rate =
          predict_range(*s, t0_.plus_seconds(t_doppler_s), kClockBias0_m + kClockDrift_mps * t_doppler_s,
                        at_doppler.r_ecef_m, at_doppler.v_ecef_mps, nav_.iono);
      GpsL1Observation o;
      o.prn = s->prn;
      o.pseudorange_m = code.pseudorange_m(bias_m) + spec_.pseudorange_sigma_m * n01(rng);
      o.doppler_hz =
          -(rate.pseudorange_rate_mps(at_doppler.v_ecef_mps, kClockDrift_mps) + spec_.rate_sigma_mps * n01(rng)) /
          gps::kL1Wavelength_m;
      o.cn0_dbhz = 45.0;
      e.gps.push_back(o);
    }
    return e;
  }

  RecordingSpec spec_;
  SimulatedRun run_;
  NavData nav_;
  GpsTime t0_;
  std::vector<const Ephemeris*> satellites_;
  ObservationFile obs_;
  ImuLog imu_;
};

/// What the run published at one epoch, and its error against the truth.
struct PublishedEpoch {
  double t_s = 0.0;  ///< trajectory time
  std::string mode;
  bool from_filter = false;
  int filter_satellites = 0;
  Eigen::Vector3d error_ned_m = Eigen::Vector3d::Zero();
};

struct FusionOutcome {
  std::vector<PublishedEpoch> epochs;
  std::vector<FusionEpochTrace> traces;
  RecordedFusionReport report;
};

FusionOutcome fuse(SyntheticRecording& rec, const RecordedFusionConfig& config) {
  FusionOutcome out;
  RecordedFusion fusion(config, rec.observations(), rec.navigation(), rec.imu());
  fusion.set_trace([&](const FusionEpochTrace& t) { out.traces.push_back(t); });
  CallbackSink sink([&](const NavigationEpoch& e) {
    PublishedEpoch p;
    p.t_s = rec.seconds_of(*e.receiver.t_rx);
    p.mode = std::string(e.mode);
    p.from_filter = e.from_filter;
    p.filter_satellites = e.filter_satellites;
    if (e.solution.valid) p.error_ned_m = ned_offset_m(rec.trajectory().at(p.t_s).r_ecef_m, e.solution.r_ecef_m);
    out.epochs.push_back(p);
  });
  fusion.run({&sink});
  out.report = fusion.report();
  return out;
}

/// Horizontal RMS error (m) of the filter's solutions from t_from_s on.
double horizontal_rms_m(const FusionOutcome& o, double t_from_s) {
  double sum = 0.0;
  int n = 0;
  for (const PublishedEpoch& p : o.epochs)
    if (p.from_filter && p.t_s >= t_from_s) sum += p.error_ned_m.head<2>().squaredNorm(), ++n;
  return n > 0 ? std::sqrt(sum / n) : 1e9;
}

class RecordedFusionModes : public ::testing::TestWithParam<NavMode> {};

TEST_P(RecordedFusionModes, StartsConvergesAndLabelsItsEpochs) {
  SyntheticRecording rec({});
  ASSERT_GE(rec.satellites(), 6u);
  const NavMode mode = GetParam();
  const FusionOutcome o = fuse(rec, rec.config(mode));
  ASSERT_EQ(o.epochs.size(), 121u);
  EXPECT_EQ(o.report.epochs, 121);
  EXPECT_EQ(o.report.fixes, 121);
  ASSERT_TRUE(o.report.ins_start_t_s.has_value());
  EXPECT_EQ(o.report.ins_start, "moving: TRIAD of specific force and direction of travel");
  EXPECT_LE(*o.report.ins_start_t_s, 5.0);
  EXPECT_EQ(o.report.filter_restarts, 0);
  // The receiver's PVT until the INS starts (that epoch included), the filter after.
  int filter_epochs = 0;
  for (const PublishedEpoch& p : o.epochs) {
    const bool started = p.t_s > *o.report.ins_start_t_s + 0.5;
    EXPECT_EQ(p.from_filter, p.t_s >= *o.report.ins_start_t_s - 0.5) << "t = " << p.t_s;
    if (p.from_filter) ++filter_epochs;
    if (started) {
      EXPECT_EQ(p.mode, to_string(mode)) << "t = " << p.t_s;
      // Tight: every satellite's rows; loose: the PVT's satellites (RAIM may leave one out).
      if (mode == NavMode::tight) {
        EXPECT_EQ(p.filter_satellites, static_cast<int>(rec.satellites())) << "t = " << p.t_s;
      }
      EXPECT_GE(p.filter_satellites, static_cast<int>(rec.satellites()) - 1) << "t = " << p.t_s;
    } else if (!p.from_filter) {
      EXPECT_EQ(p.mode, "scalar") << "t = " << p.t_s;
    }
  }
  EXPECT_EQ(o.report.filter_epochs, filter_epochs);
  EXPECT_DOUBLE_EQ(o.report.seconds_in_mode.at(to_string(mode)), filter_epochs);
  EXPECT_DOUBLE_EQ(o.report.seconds_in_mode.at("scalar"), 121 - filter_epochs);
  // Converged: over the last minute well inside the 1 m pseudorange noise's PVT scatter.
  EXPECT_LT(horizontal_rms_m(o, 60.0), 1.0);
  for (const PublishedEpoch& p : o.epochs) {
    if (p.t_s >= 60.0) {
      EXPECT_LT(std::abs(p.error_ned_m(2)), 3.0) << "t = " << p.t_s;
    }
  }
}

TEST(RecordedFusion, CoastsAcrossMissingEpochsAndFewSatellites) {
  SyntheticRecording rec({});
  // Ten epochs missing from the file (t = 60 .. 69 s), and two satellites only at t = 80 s.
  std::vector<ObservationEpoch>& epochs = rec.observations().epochs;
  epochs.erase(epochs.begin() + 60, epochs.begin() + 70);
  ObservationEpoch& sparse = epochs[70];
  ASSERT_NEAR(rec.seconds_of(sparse.t), 80.0, 1e-9);
  sparse.gps.resize(2);
  const FusionOutcome o = fuse(rec, rec.config(NavMode::tight));
  ASSERT_EQ(o.epochs.size(), 111u);
  EXPECT_EQ(o.report.filter_restarts, 0);
  for (std::size_t i = 0; i < o.epochs.size(); ++i) {
    const PublishedEpoch& p = o.epochs[i];
    if (p.t_s < 59.5) continue;
    EXPECT_TRUE(p.from_filter) << "t = " << p.t_s;
    EXPECT_EQ(p.mode, "tight") << "t = " << p.t_s;
    if (std::abs(p.t_s - 70.0) < 0.5) {
      // The first epoch after the gap: 10 s on the IMU alone, then the rows.
      EXPECT_LT(p.error_ned_m.head<2>().norm(), 2.0);
      EXPECT_EQ(o.traces[i].rows, 2 * static_cast<int>(rec.satellites()));
    }
    if (std::abs(p.t_s - 80.0) < 0.5) {
      EXPECT_FALSE(o.traces[i].pvt_valid);  // two satellites make no fix
      EXPECT_EQ(p.filter_satellites, 2);
      EXPECT_EQ(o.traces[i].rows, 4);
      EXPECT_LT(p.error_ned_m.head<2>().norm(), 2.0);
    }
  }
  EXPECT_LT(horizontal_rms_m(o, 60.0), 1.0);
}

TEST_P(RecordedFusionModes, StopsTheInsWhereTheImuLogHasNoData) {
  // 6 s without IMU data (40 s to 46 s) and a log that ends at 90 s: no solution there may
  // come from the INS, which never saw the motion; the single point is published, labelled
  // so, and the INS starts again after the gap.
  SyntheticRecording rec({});
  rec.cut_imu(40.0, 46.0);
  rec.cut_imu(90.0, 1e9);
  const FusionOutcome o = fuse(rec, rec.config(GetParam()));
  EXPECT_EQ(o.report.imu_gap_stops, 1);
  ASSERT_TRUE(o.report.imu_end_t_s.has_value());
  EXPECT_NEAR(*o.report.imu_end_t_s, 90.0, 1e-6);
  bool filter_after_gap = false;
  for (const PublishedEpoch& p : o.epochs) {
    const bool no_imu = (p.t_s > 40.5 && p.t_s < 46.5) || p.t_s > 90.5;
    if (no_imu) {
      EXPECT_FALSE(p.from_filter) << "t = " << p.t_s;
      EXPECT_EQ(p.mode, "scalar") << "t = " << p.t_s;
    }
    if (p.t_s > 46.0 && p.t_s < 90.0 && p.from_filter) filter_after_gap = true;
    EXPECT_LT(p.error_ned_m.head<2>().norm(), 5.0) << "t = " << p.t_s;
  }
  EXPECT_TRUE(filter_after_gap);
  EXPECT_LT(horizontal_rms_m(o, 60.0), 1.0);
}

TEST(RecordedFusion, RestartsAFilterThatTurnsAwayItsRows) {
  // Pseudoranges weighed as if a hundred times better than their 1 m of noise: the gate
  // turns most rows away and the filter no longer agrees with the observations; the
  // innovation monitor restarts it each time (as `deepnav run` does) rather than let it
  // run on unwatched.
  SyntheticRecording rec({});
  RecordedFusionConfig c = rec.config(NavMode::tight);
  c.pseudorange_sigma_scale = 0.01;
  const FusionOutcome o = fuse(rec, c);
  EXPECT_GT(o.report.rows_rejected, 100);
  EXPECT_GT(o.report.filter_restarts, 5);
  for (const PublishedEpoch& p : o.epochs) EXPECT_LT(p.error_ned_m.head<2>().norm(), 10.0) << "t = " << p.t_s;
}

/// RMS over the epochs from t_from_s of the rate residuals against the filter's prior (m/s).
double rate_residual_rms_mps(const FusionOutcome& o, double t_from_s) {
  double sum = 0.0;
  int n = 0;
  for (const FusionEpochTrace& t : o.traces)
    for (const FusionSatelliteTrace& s : t.satellites)
      if (t.filter && t.t_s >= t_from_s && s.rate_residual_mps) sum += *s.rate_residual_mps * *s.rate_residual_mps, ++n;
  return n > 0 ? std::sqrt(sum / n) : 1e9;
}

TEST_P(RecordedFusionModes, TakesEachDopplerAtTheTimeItRefersTo) {
  // An aircraft turning at 0.45 g whose receiver records Dopplers 50 ms old (a window's
  // mean): told so, the filter compares them (tight) or the PVT velocity solved from them
  // (loose) with the INS there and stays on the pseudoranges; untold, it takes their
  // 0.2 m/s of lag for a velocity error, which its position follows.
  RecordingSpec spec;
  spec.trajectory = "air-circle";
  spec.duration_s = 90.0;
  spec.doppler_time_offset_s = -0.05;
  SyntheticRecording rec(spec);
  RecordedFusionConfig told = rec.config(GetParam()), untold = told;
  told.doppler_time_offset_s = -0.05;
  const FusionOutcome with_offset = fuse(rec, told), without = fuse(rec, untold);
  ASSERT_EQ(with_offset.report.filter_restarts, 0);
  ASSERT_TRUE(with_offset.report.ins_start_t_s.has_value());
  if (GetParam() == NavMode::tight) {
    EXPECT_LT(rate_residual_rms_mps(with_offset, 30.0), 0.03);  // the 0.02 m/s noise and the prior's sigma
  }
  const double told_m = horizontal_rms_m(with_offset, 30.0), untold_m = horizontal_rms_m(without, 30.0);
  EXPECT_LT(told_m, 0.5);
  EXPECT_LT(told_m, 0.25 * untold_m);
}

INSTANTIATE_TEST_SUITE_P(LooseAndTight, RecordedFusionModes, ::testing::Values(NavMode::loose, NavMode::tight),
                         [](const ::testing::TestParamInfo<NavMode>& i) { return to_string(i.param); });

}  // namespace
}  // namespace deepnav::aiding
