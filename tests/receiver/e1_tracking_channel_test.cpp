// The Galileo E1 channel on a synthetic CBOC signal (tests/receiver/e1_test_signal.hpp):
// pull-in, CS25 synchronisation, pure-PLL tracking, code and carrier accuracy, symbols,
// and the BOC side-peak guard.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "e1_test_signal.hpp"
#include "receiver/tracking/e1_secondary_sync.hpp"
#include "receiver/tracking/e1_side_peak_guard.hpp"
#include "receiver/tracking/e1_tracking_channel.hpp"
#include "receiver/tracking/e1_tracking_loops.hpp"
#include "signals/galileo/e1_codes.hpp"

namespace deepnav {
namespace {

using testing::E1Signal;
using testing::E1SignalSpec;

/// Seeded random symbols, one per code period.
int random_symbol(std::int64_t period) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(period) * 7919 + 13);
  return (rng() & 1) ? -1 : 1;
}

struct RunResult {
  std::vector<E1CorrelatorEpoch> epochs;
  std::vector<double> code_error_chips;       ///< channel - signal at each epoch's end
  std::vector<double> carrier_offset_cycles;  ///< signal - NCO phase at each epoch's end
  std::vector<double> epoch_end_s;
};

/// Tracks `seconds` of the signal with the channel's own loops.
RunResult track(E1Signal& signal, E1TrackingChannel& channel, E1LoopController& loops, double seconds) {
  RunResult r;
  const double fs = signal.spec().fs_hz;
  const int blocks = static_cast<int>(std::lround(seconds / 0.01));
  for (int b = 0; b < blocks; ++b) {
    const SampleBlock block = signal.next(10);
    channel.process(block, [&](const E1CorrelatorEpoch& e) {
      channel.apply(loops.update(e));
      const std::int64_t end = e.first_sample + e.samples;
      const double t = static_cast<double>(end) / fs;
      r.code_error_chips.push_back(channel.code_chips_at(end) - signal.code_chips(t));
      r.carrier_offset_cycles.push_back(signal.carrier_cycles(t) - e.carrier_phase_cycles);
      r.epoch_end_s.push_back(t);
      r.epochs.push_back(e);
    });
  }
  return r;
}

/// Distance of x from the nearest value target + whole cycles.
double cycles_from(double x, double target) {
  const double d = x - target;
  return d - std::round(d);
}

E1ChannelStart start_near(const E1Signal& signal, double code_error_chips, double doppler_error_hz) {
  E1ChannelStart start;
  start.satellite = SatelliteId{GnssSystem::galileo, signal.spec().prn};
  start.code_phase_chips = signal.spec().code0_chips + code_error_chips;
  start.doppler_hz = signal.spec().doppler0_hz + doppler_error_hz;
  return start;
}

E1TrackingConfig config_for(const E1Signal& signal) {
  E1TrackingConfig cfg;
  cfg.sample_rate_hz = signal.spec().fs_hz;
  return cfg;
}

TEST(E1TrackingChannel, LocksSynchronisesAndTracksAt45DbHz) {
  E1SignalSpec spec;
  spec.symbol = random_symbol;
  E1Signal signal(spec);
  E1TrackingChannel channel(config_for(signal), start_near(signal, 0.08, 25.0));
  E1LoopController loops(spec.doppler0_hz + 25.0);
  const RunResult r = track(signal, channel, loops, 1.6);

  ASSERT_EQ(channel.state(), E1ChannelState::tracking);
  ASSERT_TRUE(channel.secondary_phase().has_value());
  EXPECT_EQ(channel.side_peak_jumps(), 0);
  const E1CorrelatorEpoch& last = r.epochs.back();
  EXPECT_TRUE(last.secondary_synced);
  EXPECT_NEAR(last.integration_s, 0.020, 1e-4);
  EXPECT_TRUE(last.pll_lock);
  EXPECT_TRUE(last.code_lock);
  EXPECT_NEAR(last.cn0_dbhz, 45.0, 1.5);
  EXPECT_NEAR(last.carrier_doppler_hz, signal.doppler_hz(r.epoch_end_s.back()), 3.0);

  int checked = 0, symbol_errors = 0;
  for (std::size_t k = 0; k < r.epochs.size(); ++k) {
    if (r.epoch_end_s[k] < 1.0) continue;
    // Code within 0.05 chip; the wiped pilot sits at half a cycle from the signal's carrier
    // (the ICD's composite sends E1-C in antiphase) without any half-cycle slip.
    EXPECT_LT(std::abs(r.code_error_chips[k]), 0.05) << "at " << r.epoch_end_s[k] << " s";
    EXPECT_LT(std::abs(cycles_from(r.carrier_offset_cycles[k], 0.5)), 0.06) << "at " << r.epoch_end_s[k] << " s";
    for (const E1bSymbol& s : r.epochs[k].symbols) {
      ASSERT_TRUE(s.polarity_known);
      ++checked;
      if ((s.soft > 0.0 ? 1 : -1) != random_symbol(s.code_period)) ++symbol_errors;
    }
  }
  EXPECT_GT(checked, 140);
  EXPECT_EQ(symbol_errors, 0);
}

TEST(E1TrackingChannel, TracksAt35DbHz) {
  E1SignalSpec spec;
  spec.cn0_dbhz = 35.0;
  spec.prn = 4;
  spec.code0_chips = 3021.7;
  spec.doppler0_hz = -2200.0;
  spec.doppler_rate_hzps = -1.5;
  spec.seed = 8;
  spec.symbol = random_symbol;
  E1Signal signal(spec);
  E1TrackingChannel channel(config_for(signal), start_near(signal, -0.05, -15.0));
  E1LoopController loops(spec.doppler0_hz - 15.0);
  const RunResult r = track(signal, channel, loops, 2.0);

  ASSERT_EQ(channel.state(), E1ChannelState::tracking);
  ASSERT_TRUE(channel.secondary_phase().has_value());
  EXPECT_NEAR(r.epochs.back().cn0_dbhz, 35.0, 2.0);
  double sum2 = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < r.epochs.size(); ++k) {
    if (r.epoch_end_s[k] < 1.3) continue;
    EXPECT_LT(std::abs(r.code_error_chips[k]), 0.1);
    EXPECT_LT(std::abs(cycles_from(r.carrier_offset_cycles[k], 0.5)), 0.15);
    sum2 += r.code_error_chips[k] * r.code_error_chips[k];
    ++n;
  }
  ASSERT_GT(n, 20);
  EXPECT_LT(std::sqrt(sum2 / n), 0.05);
}

TEST(E1TrackingChannel, JumpsFromASidePeakBackToTheMainPeak) {
  E1SignalSpec spec;
  spec.seed = 21;
  spec.symbol = random_symbol;
  E1Signal signal(spec);
  // Half a chip late: the prompt sits on the BOC(1,1) side peak, where the DLL alone stays.
  E1TrackingChannel channel(config_for(signal), start_near(signal, -0.5, 10.0));
  E1LoopController loops(spec.doppler0_hz + 10.0);
  const RunResult r = track(signal, channel, loops, 1.4);

  // Asserted outcome: pulled back to the main peak by one jump, not dropped.
  ASSERT_NE(channel.state(), E1ChannelState::lost);
  EXPECT_EQ(channel.side_peak_jumps(), 1);
  ASSERT_EQ(channel.state(), E1ChannelState::tracking);
  for (std::size_t k = 0; k < r.epochs.size(); ++k) {
    if (r.epoch_end_s[k] < 1.1) continue;
    EXPECT_LT(std::abs(r.code_error_chips[k]), 0.05);
    EXPECT_LT(std::abs(cycles_from(r.carrier_offset_cycles[k], 0.5)), 0.06);
  }
}

TEST(E1TrackingChannel, StaysOnASidePeakWithoutTheGuard) {
  // The same start with the very-early/very-late taps off: the false lock the guard exists for.
  E1SignalSpec spec;
  spec.seed = 21;
  E1Signal signal(spec);
  E1TrackingConfig cfg = config_for(signal);
  cfg.very_spacing_chips = 0.0;
  E1TrackingChannel channel(cfg, start_near(signal, -0.5, 10.0));
  E1LoopController loops(spec.doppler0_hz + 10.0);
  const RunResult r = track(signal, channel, loops, 0.6);
  ASSERT_NE(channel.state(), E1ChannelState::lost);
  EXPECT_NEAR(r.code_error_chips.back(), -0.5, 0.1);
}

TEST(E1TrackingChannel, DeclaresLossWhenNoJumpIsAllowed) {
  // The other outcome of the guard: with no jump allowed, a side-peak lock ends the channel.
  E1SignalSpec spec;
  spec.seed = 21;
  E1Signal signal(spec);
  E1TrackingConfig cfg = config_for(signal);
  cfg.side_peak_max_jumps = 0;
  E1TrackingChannel channel(cfg, start_near(signal, -0.5, 10.0));
  E1LoopController loops(spec.doppler0_hz + 10.0);
  track(signal, channel, loops, 0.6);
  EXPECT_EQ(channel.state(), E1ChannelState::lost);
  EXPECT_EQ(channel.side_peak_jumps(), 1);
}

TEST(E1TrackingChannel, DeclaresLossWhenNoSecondaryCodeIsFound) {
  // A pilot without CS25: the channel locks its carrier but never finds a phase, and gives up.
  E1SignalSpec spec;
  spec.secondary_code = false;
  E1Signal signal(spec);
  E1TrackingConfig cfg = config_for(signal);
  cfg.secondary_timeout_s = 0.5;
  E1TrackingChannel channel(cfg, start_near(signal, 0.0, 5.0));
  E1LoopController loops(spec.doppler0_hz + 5.0);
  const RunResult r = track(signal, channel, loops, 1.0);
  EXPECT_EQ(channel.state(), E1ChannelState::lost);
  EXPECT_FALSE(channel.secondary_phase().has_value());
  EXPECT_NEAR(r.epochs.back().first_sample + r.epochs.back().samples, 0.8 * spec.fs_hz, 0.01 * spec.fs_hz);
}

TEST(E1TrackingChannel, DeclaresLossOnNoise) {
  E1SignalSpec spec;
  spec.cn0_dbhz = -20.0;  // nothing there
  E1Signal signal(spec);
  E1TrackingConfig cfg = config_for(signal);
  E1TrackingChannel channel(cfg, start_near(signal, 0.0, 0.0));
  E1LoopController loops(spec.doppler0_hz);
  track(signal, channel, loops, 1.6);
  EXPECT_EQ(channel.state(), E1ChannelState::lost);
}

TEST(E1SecondaryCodeSynchronizer, FindsThePhaseAndTheCarrierSideFromNoisyPrompts) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int true_offset : {0, 7, 24}) {
    for (double carrier_sign : {1.0, -1.0}) {
      SecondaryCodeSynchronizer sync;
      std::optional<SecondaryCodePhase> found;
      const double rotation = 0.3;  // rad per period: a 12 Hz frequency error
      for (std::int64_t p = 100; p < 400 && !found; ++p) {
        const std::complex<double> prompt =
            carrier_sign * 3.4 * secondary_chip(p, true_offset) * std::polar(1.0, 0.1 + rotation * (p - 100) / 50.0) +
            std::complex<double>(noise(rng), noise(rng));
        found = sync.add(p, prompt);
      }
      ASSERT_TRUE(found.has_value());
      EXPECT_EQ(found->offset, true_offset);
      EXPECT_EQ(found->prompt_sign, carrier_sign > 0 ? 1 : -1);
    }
  }
}

TEST(E1SecondaryCodeSynchronizer, FindsNothingInNoise) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 1.0);
  SecondaryCodeSynchronizer sync;
  int found = 0;
  for (std::int64_t p = 0; p < 2000; ++p)
    if (sync.add(p, {noise(rng), noise(rng)})) ++found;
  EXPECT_EQ(found, 0);  // of 1951 full windows
}

TEST(E1SidePeakGuard, JumpsTowardTheStrongerOuterTapOnlyWhenItKeepsWinning) {
  SidePeakGuard guard(5, 1);
  // On the main peak: outer taps at half the prompt.
  for (int k = 0; k < 50; ++k) EXPECT_EQ(guard.add({0.5, 0}, {1, 0}, {0.5, 0}), 0.0);
  // On a side peak late of the main one: very early sees the main peak.
  double jump = 0.0;
  for (int k = 0; k < 5; ++k) jump = guard.add({1, 0}, {-0.5, 0}, {0, 0});
  EXPECT_EQ(jump, 0.5);
  EXPECT_EQ(guard.jumps(), 1);
  EXPECT_FALSE(guard.exhausted());
  for (int k = 0; k < 5; ++k) jump = guard.add({0, 0}, {-0.5, 0}, {1, 0});
  EXPECT_EQ(jump, -0.5);
  EXPECT_TRUE(guard.exhausted());
}

TEST(E1Discriminators, Boc11DllReadsTheCodeErrorOnTheMainPeak) {
  const auto r = [](double t) { return std::abs(t) <= 0.5 ? 1.0 - 3.0 * std::abs(t) : std::abs(t) - 1.0; };
  const double d = 0.2;
  for (double err : {-0.1, -0.05, 0.0, 0.03, 0.1}) {
    // Signal ahead of the replica by err: the early tap (replica + d/2) is err - d/2 away.
    const double e = r(err - d / 2), l = r(err + d / 2);
    EXPECT_NEAR(boc11_dll_code_error_chips({e, 0}, {l, 0}, d), err, 1e-12);
  }
  // Beyond d/2 it under-reads but keeps the sign, up to the zero crossing at 1/3 chip.
  const double far = boc11_dll_code_error_chips({r(0.25 - d / 2), 0}, {r(0.25 + d / 2), 0}, d);
  EXPECT_GT(far, 0.1);
  EXPECT_LT(far, 0.25);
  EXPECT_NEAR(pilot_phase_error_cycles(std::polar(1.0, 2.0)), 2.0 / (2 * M_PI), 1e-12);
  EXPECT_NEAR(pilot_phase_error_cycles(std::polar(1.0, -2.5)), -2.5 / (2 * M_PI), 1e-12);
}

TEST(E1TrackingChannel, BadSettingsAreRejected) {
  E1ChannelStart start;
  start.satellite = SatelliteId{GnssSystem::galileo, 11};
  E1TrackingConfig cfg;
  cfg.coherent_ms_after_sync = 10;
  EXPECT_THROW(E1TrackingChannel(cfg, start), std::invalid_argument);
  cfg = {};
  cfg.spacing_chips = 0.8;
  EXPECT_THROW(E1TrackingChannel(cfg, start), std::invalid_argument);
  cfg = {};
  cfg.sample_rate_hz = 2.0e6;
  EXPECT_THROW(E1TrackingChannel(cfg, start), std::invalid_argument);
  cfg = {};
  start.satellite = SatelliteId{GnssSystem::gps, 11};
  EXPECT_THROW(E1TrackingChannel(cfg, start), std::invalid_argument);
  start.satellite = SatelliteId{GnssSystem::galileo, 51};
  EXPECT_THROW(E1TrackingChannel(cfg, start), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
