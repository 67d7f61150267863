// The filter's side of ultra-tight tracking against one synthetic channel whose signal is
// what the filter's geometry says (a satellite of data/brdc0010.22n seen from a static
// antenna, the receiver clock off by a bias and a drift): it steers the channel's NCOs by
// its prediction, measures the signal through the channel's discriminators (not the
// replica it commanded), gives back a channel it disagrees with by chips, and predicts an
// untracked signal for a guided search.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "aiding/ultra_tight_tracker.hpp"
#include "ins/frames.hpp"
#include "receiver/pvt/range_model.hpp"
#include "steered_channel_rig.hpp"

namespace deepnav::aiding {
namespace {

using testing::kRigSampleRate_hz;
using testing::kRigWeek;
using testing::SteeredChannelRig;

constexpr double kDeg = M_PI / 180.0;
constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;

/// The highest satellite of the navigation file at `t` from `r_ecef_m`.
Ephemeris highest_satellite(const NavData& nav, const GpsTime& t, const Eigen::Vector3d& r_ecef_m) {
  std::optional<Ephemeris> best;
  double best_elevation = -1.0;
  for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
    const Ephemeris* e = nav.select(prn, t);
    if (!e) continue;
    const double el = predict_range(*e, t, 0.0, r_ecef_m, Eigen::Vector3d::Zero(), IonoParameters{}).elevation_rad;
    if (el > best_elevation) best_elevation = el, best = *e;
  }
  if (!best) throw std::runtime_error("no satellite in brdc0010.22n");
  return *best;
}

/// A static antenna, its receiver clock, one satellite's signal through a steered channel,
/// and the tracker with a navigator that believes the clock is `navigator_bias_error_m` off.
class SteeredScene {
 public:
  explicit SteeredScene(double navigator_bias_error_m = 0.0)
      : r_ecef_m_(wgs84::llh_to_ecef(site_)),
        eph_(highest_satellite(testing::broadcast_navigation_data(), t0_, r_ecef_m_)),
        rig_(signal(), eph_, nullptr),
        tracker_(UltraTightConfig{}, kRigSampleRate_hz, RangeErrorModel{}, nullptr, atmosphere_),
        nav_(navigator_state(), kBias0_m + navigator_bias_error_m, kDrift_mps, NavigatorConfig{},
             InitialUncertainty{}) {
    tracker_.set_engagement(Engagement::all);
  }

  /// One 20 ms block: tracked through the tracker's controller, the tracker's update (when
  /// `measure`) and its commands, carried out between blocks (returned).
  ChannelDecision block(bool measure, KalmanUpdate* update = nullptr) {
    rig_.track(20, *tracker_.controller_for(eph_.prn));
    const KalmanUpdate r = tracker_.update_and_steer(nav_, snapshot(), measure);
    if (update) *update = r;
    return rig_.between_blocks(*tracker_.controller_for(eph_.prn));
  }

  /// Between blocks without a block: what the tracker published, carried out.
  ChannelDecision collect() { return rig_.between_blocks(*tracker_.controller_for(eph_.prn)); }

  BlockSnapshot snapshot() const {
    BlockSnapshot b;
    b.end_sample = rig_.end_sample();
    b.sample_rate_hz = kRigSampleRate_hz;
    b.clock = ReceiverClockReference{t0_, 0, kRigSampleRate_hz};
    b.tracked_prns = {eph_.prn};
    ChannelStatus ch;
    ch.prn = eph_.prn;
    ch.state = rig_.channel().state();
    ch.bit_synced = rig_.channel().bit_edge_period().has_value();
    ch.decoder_synchronised = rig_.decoder().synchronised();
    ch.cn0_dbhz = rig_.channel().cn0_dbhz();
    ch.replica_transmit_sow = transmit_time_sow(rig_.decoder(), rig_.channel(), rig_.end_sample());
    ch.ephemeris = eph_;
    b.channels = {ch};
    return b;
  }

  /// The replica's transmit time at the last block's end against the signal's (chips).
  double replica_error_chips() const {
    const std::int64_t end = rig_.end_sample();
    return (*transmit_time_sow(rig_.decoder(), rig_.channel(), end) - rig_.truth_transmit_sow(end)) *
           gps::kCodeRate_cps;
  }

  UltraTightTracker& tracker() { return tracker_; }
  AidedNavigator& nav() { return nav_; }
  const SteeredChannelRig& rig() const { return rig_; }
  const Ephemeris& ephemeris() const { return eph_; }
  double doppler_rate_hzps() const { return signal().doppler_rate_hzps; }

 private:
  static constexpr double kBias0_m = 150.0;   ///< receiver clock bias at sample 0 (c dt)
  static constexpr double kDrift_mps = 30.0;  ///< and its drift (0.1 ppm)

  /// The signal the geometry gives: transmit time and Doppler at sample 0, the Doppler's
  /// rate over the next second.
  testing::RigSignal signal() const {
    const RangePrediction now = predict_range(eph_, t0_, kBias0_m, r_ecef_m_, Eigen::Vector3d::Zero(), {}, atmosphere_);
    const RangePrediction later = predict_range(eph_, t0_.plus_seconds(1.0), kBias0_m + kDrift_mps, r_ecef_m_,
                                                Eigen::Vector3d::Zero(), {}, atmosphere_);
    const auto doppler = [](const RangePrediction& p) {
      return -p.pseudorange_rate_mps(Eigen::Vector3d::Zero(), kDrift_mps) / gps::kL1Wavelength_m;
    };
    testing::RigSignal s;
    s.transmit_sow = t0_.sow - now.pseudorange_m(kBias0_m) / gps::kSpeedOfLight_mps;
    s.doppler_hz = doppler(now);
    s.doppler_rate_hzps = doppler(later) - doppler(now);
    s.cn0_dbhz = 45.0;
    s.seed = 31;
    return s;
  }

  NavState navigator_state() const {
    NavState n;
    n.t_s = 0.0;  // sample 0
    n.llh = site_;
    return n;
  }

  const GpsTime t0_{kRigWeek, 525600.0};
  const wgs84::Llh site_{37.5 * kDeg, 127.0 * kDeg, 50.0};
  const AtmosphereModels atmosphere_{};
  Eigen::Vector3d r_ecef_m_;
  Ephemeris eph_;
  SteeredChannelRig rig_;
  UltraTightTracker tracker_;
  AidedNavigator nav_;
};

TEST(UltraTightTracker, SteersItsChannelByTheFiltersPrediction) {
  SteeredScene scene;
  int commands = 0;
  double worst_doppler_hz = 0.0, worst_correction_chips = 0.0;
  for (int k = 0; k < 100; ++k) {  // 2 s
    const ChannelDecision d = scene.block(false);
    ASSERT_TRUE(d.command.has_value());
    ++commands;
    worst_doppler_hz = std::max(worst_doppler_hz, std::abs(d.command->carrier_doppler_hz -
                                                           scene.rig().truth_doppler_hz(scene.rig().end_sample())));
    EXPECT_NEAR(d.command->code_rate_cps, gps::kCodeRate_cps * (1.0 + d.command->carrier_doppler_hz / gps::kL1_Hz),
                1e-6);
    if (k >= 25)
      worst_correction_chips = std::max(worst_correction_chips, std::abs(*d.command->code_phase_correction_chips));
  }
  EXPECT_EQ(commands, 100);
  EXPECT_LT(worst_doppler_hz, 0.05);
  EXPECT_LT(worst_correction_chips, 0.02);  // the replica stays where the filter puts it
  EXPECT_LT(std::abs(scene.replica_error_chips()), 0.02);
  EXPECT_EQ(scene.tracker().steered_channels(), 1);
  EXPECT_EQ(UltraTightTracker::count_steerable(scene.snapshot()), 1);

  scene.tracker().release_all();
  EXPECT_EQ(scene.tracker().steered_channels(), 0);
  const ChannelDecision released = scene.collect();
  EXPECT_FALSE(released.command.has_value());
  EXPECT_EQ(released.loss_detection, std::optional<bool>(true));
}

TEST(UltraTightTracker, MeasuresTheSignalNotTheReplicaItCommanded) {
  // The filter's clock is 60 m (0.2 chip) ahead of the receiver's: it steers the replica
  // there, and the discriminators show the signal 60 m short of its prediction.
  SteeredScene scene(60.0);
  for (int k = 0; k < 50; ++k) scene.block(false);
  EXPECT_NEAR(scene.replica_error_chips(), -60.0 / kChip_m, 0.05);
  EXPECT_EQ(scene.tracker().measuring_channels(), 0);
  const double bias_before_m = scene.nav().clock_bias_m();
  KalmanUpdate update;
  scene.block(true, &update);
  EXPECT_EQ(scene.tracker().measuring_channels(), 1);
  EXPECT_TRUE(update.applied);
  EXPECT_GE(update.rows, 2);  // each integration's pseudorange, and rates once windows close
  const std::vector<RangeResidual> residuals = scene.tracker().mean_pseudorange_residuals();
  ASSERT_EQ(residuals.size(), 1u);
  EXPECT_NEAR(residuals[0].residual_m, -60.0, 12.0);  // two 10 ms integrations: 4 m each
  EXPECT_GT(residuals[0].elevation_rad, 10.0 * kDeg);
  // The update takes part of it into the clock.
  EXPECT_LT(scene.nav().clock_bias_m(), bias_before_m - 5.0);
  scene.tracker().clear_pseudorange_residuals();
  EXPECT_TRUE(scene.tracker().mean_pseudorange_residuals().empty());
}

TEST(UltraTightTracker, MovesTheReplicaByTheFiltersCorrectionAndGivesBackAChannelChipsAway) {
  SteeredScene scene;
  for (int k = 0; k < 25; ++k) scene.block(false);
  // The filter's clock jumps 300 m (about a chip): the replica is moved there.
  scene.nav().shift_clock_bias(300.0);
  const ChannelDecision moved = scene.block(false);
  ASSERT_TRUE(moved.command.has_value());
  EXPECT_NEAR(*moved.command->code_phase_correction_chips, -300.0 / kChip_m, 0.05);
  EXPECT_EQ(scene.tracker().steered_channels(), 1);
  // 2 km more (over 5 chips): not a tracking error, the channel goes back to its own loops.
  scene.nav().shift_clock_bias(2000.0);
  const ChannelDecision released = scene.block(false);
  EXPECT_FALSE(released.command.has_value());
  EXPECT_EQ(released.loss_detection, std::optional<bool>(true));
  EXPECT_EQ(scene.tracker().steered_channels(), 0);
}

TEST(UltraTightTracker, PredictsAnUntrackedSignalForAGuidedSearch) {
  SteeredScene scene;
  for (int k = 0; k < 5; ++k) scene.block(false);
  const BlockSnapshot snap = scene.snapshot();
  const std::optional<SignalPrediction> p =
      scene.tracker().predict_signal(scene.ephemeris().prn, scene.ephemeris(), scene.nav(), snap, 5.0 * kDeg);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->sample, snap.end_sample);
  EXPECT_NEAR((p->transmit_sow - scene.rig().truth_transmit_sow(snap.end_sample)) * gps::kCodeRate_cps, 0.0, 0.01);
  EXPECT_NEAR(p->doppler_hz, scene.rig().truth_doppler_hz(snap.end_sample), 0.05);
  EXPECT_NEAR(p->doppler_rate_hzps, scene.doppler_rate_hzps(), 0.01);
  // The covariance's range sigma with the broadcast orbit's 3 m on top.
  EXPECT_GT(p->code_sigma_chips, 3.0 / kChip_m);
  EXPECT_GT(p->doppler_sigma_hz, 0.0);
  // Below the mask, or without the receiver clock: nothing to search for.
  EXPECT_FALSE(
      scene.tracker()
          .predict_signal(scene.ephemeris().prn, scene.ephemeris(), scene.nav(), snap, p->elevation_deg * kDeg + 0.01)
          .has_value());
  BlockSnapshot no_clock = snap;
  no_clock.clock.reset();
  EXPECT_FALSE(scene.tracker()
                   .predict_signal(scene.ephemeris().prn, scene.ephemeris(), scene.nav(), no_clock, 5.0 * kDeg)
                   .has_value());
}

TEST(UltraTightTracker, CountsOnlyChannelsItCouldTakeOver) {
  BlockSnapshot b;
  const auto channel = [](int prn, ChannelState state, bool bit_synced, bool decoder, bool ephemeris) {
    ChannelStatus c;
    c.prn = prn;
    c.state = state;
    c.bit_synced = bit_synced;
    c.decoder_synchronised = decoder;
    if (ephemeris) c.ephemeris = Ephemeris{};
    return c;
  };
  b.channels = {
      channel(1, ChannelState::tracking, true, true, true),  channel(2, ChannelState::tracking, false, true, true),
      channel(3, ChannelState::lost, true, true, true),      channel(4, ChannelState::tracking, true, false, true),
      channel(5, ChannelState::tracking, true, true, false), channel(6, ChannelState::tracking, true, true, true)};
  EXPECT_EQ(UltraTightTracker::count_steerable(b), 2);
}

}  // namespace
}  // namespace deepnav::aiding
