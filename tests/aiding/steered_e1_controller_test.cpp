// The steered side of a Galileo E1 channel: the filter takes a channel over only once it can
// place its replica (pilot tracked, code periods dated by I/NAV, ephemeris, clock, the
// Galileo system offset), its integrations come back as discriminator samples that measure
// where the signal is, a weak signal is integrated 100 ms coherently on the pilot and still
// measured, a sudden fade widens the samples' sigma at once, and a release gives the channel
// back to its own loops and loss rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "../receiver/e1_test_signal.hpp"
#include "../receiver/inav_test_message.hpp"
#include "aiding/measurement_models.hpp"
#include "aiding/steered_e1_controller.hpp"
#include "receiver/tracking/e1_tracking_loops.hpp"

namespace deepnav::aiding {
namespace {

constexpr int kFirstSymbol = 350;  // the signal starts 150 symbols before page 1
constexpr int kCoherentPeriods = 5;

/// An E1 channel on a synthetic signal carrying I/NAV pages with the time (word 0), driven
/// the way the receiver drives one: each integration to the controller (its decisions
/// carried out) or, when it does not take it, to the channel's own loops; the E1-B symbols to
/// the decoder; between blocks what the controller published. `filter` stands for the
/// navigation filter: it publishes the true Doppler after each block while the controller
/// steers.
class SteeredE1Rig {
 public:
  explicit SteeredE1Rig(double cn0_dbhz)
      : levels_(::deepnav::testing::inav_test_symbols(std::vector<int>(8, 0))),
        signal_(spec(cn0_dbhz, levels_)),
        channel_(config(), start()),
        loops_(start().doppler_hz),
        decoder_(::deepnav::testing::kInavTestSvid),
        ephemeris_(::deepnav::testing::inav_test_ephemeris()) {}

  /// `ms` of signal in 10 ms blocks.
  void track(int ms, SteeredE1Controller& controller, bool filter = true) {
    for (int b = 0; b < ms / 10; ++b) {
      channel_.process(signal_.next(10), [&](const E1CorrelatorEpoch& e) {
        const E1ChannelDecision d = controller.on_epoch(e, view());
        carry_out(d);
        if (d.owns_epoch) {
          loops_.follow(e);
          decisions_.push_back(d);
        } else {
          channel_.apply(loops_.update(e));
        }
        decoder_.add(e.symbols);
      });
      if (filter && controller.steered()) {
        NcoCommand c;
        c.carrier_doppler_hz = signal_.doppler_hz(static_cast<double>(channel_.next_sample()) / spec_fs());
        c.code_rate_cps = galileo::kE1CodeRate_cps * (1.0 + c.carrier_doppler_hz / galileo::kE1_Hz);
        controller.publish(c);
      }
      carry_out(controller.between_blocks(view()));
    }
  }

  /// GST transmit time (seconds of week) of the signal arriving at a sample: code period p
  /// carries symbol p + kFirstSymbol, and page k (symbol 500 k) starts at kInavTestTow0 + 2 k.
  double truth_transmit_sow(std::int64_t sample) const {
    return ::deepnav::testing::kInavTestTow0 + kFirstSymbol * 0.004 +
           signal_.code_chips(static_cast<double>(sample) / spec_fs()) / galileo::kE1CodeRate_cps;
  }
  double truth_doppler_hz(std::int64_t sample) const {
    return signal_.doppler_hz(static_cast<double>(sample) / spec_fs());
  }
  void set_cn0_dbhz(double cn0_dbhz) { signal_.set_cn0_dbhz(cn0_dbhz); }
  /// Between blocks: what the controller published, carried out; returned for inspection.
  E1ChannelDecision between_blocks(SteeredE1Controller& controller) {
    const E1ChannelDecision d = controller.between_blocks(view());
    carry_out(d);
    return d;
  }

  E1ChannelView view() const { return {channel_, decoder_, &ephemeris_, true}; }
  const E1TrackingChannel& channel() const { return channel_; }
  const InavDecoder& decoder() const { return decoder_; }
  bool loss_detection() const { return loss_detection_; }
  /// The decisions of the integrations the controller took, since the last call.
  std::vector<E1ChannelDecision> take_decisions() { return std::exchange(decisions_, {}); }

 private:
  static double spec_fs() { return 4.0e6; }
  static ::deepnav::testing::E1SignalSpec spec(double cn0_dbhz, const std::vector<int>& levels) {
    ::deepnav::testing::E1SignalSpec s;
    s.fs_hz = spec_fs();
    s.prn = ::deepnav::testing::kInavTestSvid;
    s.cn0_dbhz = cn0_dbhz;
    s.code0_chips = 0.0;
    s.symbol = [&levels](std::int64_t p) {
      const auto k = static_cast<std::size_t>(p + kFirstSymbol);
      return k < levels.size() ? levels[k] : 1;
    };
    return s;
  }
  static E1TrackingConfig config() {
    E1TrackingConfig c;
    c.sample_rate_hz = spec_fs();
    c.coherent_ms_after_sync = 4 * kCoherentPeriods;
    return c;
  }
  static E1ChannelStart start() {
    E1ChannelStart st;
    st.satellite = SatelliteId{GnssSystem::galileo, ::deepnav::testing::kInavTestSvid};
    st.code_phase_chips = 0.05;
    st.doppler_hz = 1500.0 + 20.0;
    return st;
  }
  void carry_out(const E1ChannelDecision& d) {
    if (d.loss_detection) {
      channel_.set_loss_detection(*d.loss_detection);
      loss_detection_ = *d.loss_detection;
    }
    if (d.coherent_periods) channel_.set_coherent_periods(*d.coherent_periods);
    if (d.command) channel_.apply(*d.command);
  }

  std::vector<int> levels_;
  ::deepnav::testing::E1Signal signal_;
  E1TrackingChannel channel_;
  E1LoopController loops_;
  InavDecoder decoder_;
  galileo::GalileoEphemeris ephemeris_;
  std::vector<E1ChannelDecision> decisions_;
  bool loss_detection_ = true;
};

/// Signal minus replica transmit time of a sample against the truth (chips).
double measured_error_chips(const DiscriminatorSample& d, const SteeredE1Rig& rig) {
  const double measured = d.replica_transmit_sow + d.code_error_chips / galileo::kE1CodeRate_cps;
  return (measured - rig.truth_transmit_sow(d.mid_sample)) * galileo::kE1CodeRate_cps;
}

/// A 45 dB-Hz signal, the filter engaged and the Galileo offset known (unless a test says
/// otherwise before the first track()).
class SteeredE1ControllerTest : public ::testing::Test {
 protected:
  /// The first 3.5 s: pulled in, the first time mark decoded, taken over; its samples dropped.
  void take_over() {
    rig.track(3500, controller);
    ASSERT_TRUE(controller.steered());
    rig.take_decisions();
    controller.take_samples();
  }

  SteeredE1Rig rig{45.0};
  const UltraTightConfig cfg;
  Engagement engagement = Engagement::all;
  bool offset_known = true;
  SteeredE1Controller controller{cfg, 4.0e6, engagement, offset_known};
};

TEST_F(SteeredE1ControllerTest, TakesTheChannelOnlyOnceItsReplicaCanBePlaced) {
  offset_known = false;
  // Pulled in and tracking the pilot, the first page with the time decoded: still its own
  // loops while the Galileo system offset is unknown.
  rig.track(3500, controller);
  ASSERT_EQ(rig.channel().state(), E1ChannelState::tracking);
  ASSERT_TRUE(rig.decoder().navigation().time_mark().has_value());
  EXPECT_FALSE(controller.steered());
  EXPECT_TRUE(rig.take_decisions().empty());
  EXPECT_TRUE(controller.take_samples().empty());

  offset_known = true;
  rig.track(20, controller);
  const std::vector<E1ChannelDecision> first = rig.take_decisions();
  ASSERT_FALSE(first.empty());
  EXPECT_TRUE(controller.steered());
  EXPECT_EQ(first.front().loss_detection, std::optional<bool>(false));
  EXPECT_EQ(first.front().coherent_periods, std::optional<int>(cfg.e1_coherent_ms / 4));
  EXPECT_FALSE(rig.loss_detection());
}

TEST_F(SteeredE1ControllerTest, SamplesMeasureTheSignalAndTheLoopHoldsItsPhase) {
  take_over();
  rig.track(2000, controller);
  const std::vector<DiscriminatorSample> samples = controller.take_samples();
  ASSERT_GE(samples.size(), 90u);  // 20 ms integrations
  int measurements = 0, rates = 0;
  for (const DiscriminatorSample& d : samples) {
    EXPECT_EQ(d.satellite(), (SatelliteId{GnssSystem::galileo, ::deepnav::testing::kInavTestSvid}));
    EXPECT_NEAR(d.integration_s, 0.02, 1e-3);
    EXPECT_NEAR(measured_error_chips(d, rig), 0.0, 0.03);  // 9 m; the discriminator's sigma is 0.008 chips
    if (d.measurement) ++measurements;
    if (d.doppler_hz) {
      ++rates;
      EXPECT_GT(d.rate_window_s, 0.08);  // phase locked: carrier phase windows
      EXPECT_NEAR(*d.doppler_hz, rig.truth_doppler_hz(d.doppler_sample), 0.2);
    }
  }
  EXPECT_EQ(measurements, static_cast<int>(samples.size()));
  EXPECT_GE(rates, 15);  // about one a 100 ms window
  // The phase loop keeps the wiped pilot's prompt on the real axis: the decisions say locked.
  const std::vector<E1ChannelDecision> decisions = rig.take_decisions();
  ASSERT_FALSE(decisions.empty());
  ASSERT_TRUE(decisions.back().lock.has_value());
  EXPECT_TRUE(decisions.back().lock->locked);
  EXPECT_NEAR(decisions.back().lock->cn0_dbhz, 45.0, 2.0);
}

TEST_F(SteeredE1ControllerTest, AWeakSignalIsIntegratedLongerOnThePilotAndStillMeasured) {
  take_over();
  // 24 dB-Hz: below the channel's own loss threshold (25 dB-Hz for a second).
  rig.set_cn0_dbhz(24.0);
  rig.track(1000, controller);
  // At once, before the C/N0 estimate follows: the last integrations' scatter widens the sigma.
  double widest_floor = 0.0;
  for (const DiscriminatorSample& d : controller.take_samples())
    widest_floor = std::max(widest_floor, d.code_sigma_floor_chips);
  EXPECT_GT(widest_floor, 3.0 * e1_code_sigma_chips(45.0, 0.02, 0.2));
  rig.track(5000, controller);
  EXPECT_TRUE(controller.long_integration());
  EXPECT_EQ(rig.channel().coherent_periods(), cfg.e1_weak_coherent_ms / 4);
  EXPECT_NE(rig.channel().state(), E1ChannelState::lost);
  controller.take_samples();
  rig.track(3000, controller);
  const std::vector<DiscriminatorSample> samples = controller.take_samples();
  ASSERT_GE(samples.size(), 25u);
  int measurements = 0;
  double sum2 = 0.0;
  for (const DiscriminatorSample& d : samples) {
    EXPECT_NEAR(d.integration_s, 0.1, 1e-3);
    if (!d.measurement) continue;
    ++measurements;
    sum2 += std::pow(measured_error_chips(d, rig), 2);
  }
  EXPECT_GE(measurements, 20);
  // The discriminator's predicted sigma at 24 dB-Hz over 100 ms is 0.03 chips.
  EXPECT_LT(std::sqrt(sum2 / measurements), 0.06);
}

TEST_F(SteeredE1ControllerTest, AReleaseGivesTheChannelBackToItsOwnLoopsAndLossRule) {
  take_over();
  ASSERT_FALSE(rig.loss_detection());
  controller.publish_release();
  engagement = Engagement::none;
  const E1ChannelDecision d = rig.between_blocks(controller);
  EXPECT_EQ(d.loss_detection, std::optional<bool>(true));
  EXPECT_EQ(d.coherent_periods, std::optional<int>(kCoherentPeriods));
  EXPECT_TRUE(rig.loss_detection());
  rig.track(200, controller);
  EXPECT_FALSE(controller.steered());
  EXPECT_TRUE(rig.take_decisions().empty());
  EXPECT_TRUE(controller.take_samples().empty());
  // The channel's own loops hold it.
  EXPECT_EQ(rig.channel().state(), E1ChannelState::tracking);
  EXPECT_TRUE(rig.channel().phase_locked());
}

}  // namespace
}  // namespace deepnav::aiding
