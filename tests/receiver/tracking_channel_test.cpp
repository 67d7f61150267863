#include "receiver/tracking/tracking_channel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "channel_test_signal.hpp"
#include "receiver/tracking/tracking_loops.hpp"

namespace deepnav {
namespace {

using testing::ChannelSignal;
using testing::ChannelSignalSpec;

struct RunResult {
  double code_error_rms_chips = 0.0;
  double doppler_error_rms_hz = 0.0;
  double cn0_dbhz = 0.0;
  double pll_lock_time_s = -1.0;
  double bit_sync_time_s = -1.0;
  double mean_abs_very_early = 0.0, mean_abs_very_late = 0.0, mean_abs_prompt = 0.0;
  CorrelatorEpoch last;
  ChannelState final_state = ChannelState::pull_in;
};

/// Tracks `seconds` of the signal from an acquisition off by the given errors, in blocks of
/// an odd size (integrations span block boundaries), steered by the scalar loops. Errors
/// are collected after 1 s.
RunResult track(const ChannelSignalSpec& spec, double seconds, double doppler_error_hz, double code_error_chips,
                TrackingConfig cfg = {}) {
  ChannelSignal sig(spec);
  const double fs = spec.fs_hz;
  cfg.sample_rate_hz = fs;
  const double start_phase = std::fmod(spec.code0_chips, 1023.0);
  ChannelStart start{spec.prn,
                     spec.doppler0_hz + doppler_error_hz,
                     std::fmod(start_phase + code_error_chips + 1023.0, 1023.0),
                     0,
                     4,
                     std::nullopt};
  TrackingChannel ch(cfg, start);
  const LoopBandwidths pull_in{15.0, 10.0, 1.0};
  const LoopBandwidths narrow{10.0, 0.0, 0.5};
  ScalarLoopController loop(start.doppler_hz, 2, pull_in);
  RunResult r;
  double sum_code2 = 0.0, sum_dop2 = 0.0;
  int n_err = 0;
  std::vector<CorrelatorEpoch> epochs;
  const int block_ms = 50;
  for (int done_ms = 0; done_ms < seconds * 1000.0; done_ms += block_ms) {
    const SampleBlock big = sig.next(block_ms);
    for (std::size_t first = 0; first < big.samples.size(); first += 3001) {
      SampleBlock b;
      b.first_sample_index = big.first_sample_index + static_cast<std::int64_t>(first);
      b.samples.assign(big.samples.begin() + static_cast<std::ptrdiff_t>(first),
                       big.samples.begin() + static_cast<std::ptrdiff_t>(std::min(big.samples.size(), first + 3001)));
      epochs.clear();
      ch.process(b, epochs);
      for (const auto& e : epochs) {
        EXPECT_EQ(e.channel, 4);
        loop.set_bandwidths(ch.state() == ChannelState::tracking ? narrow : pull_in);
        ch.apply(loop.update(e, ch.state() == ChannelState::pull_in));
        const double t_end = static_cast<double>(e.first_sample + e.samples) / fs;
        if (r.pll_lock_time_s < 0 && e.pll_lock) r.pll_lock_time_s = t_end;
        if (r.bit_sync_time_s < 0 && e.bit_synced) r.bit_sync_time_s = t_end;
        if (t_end > 1.0) {
          const double chips = static_cast<double>(e.code_period) * 1023.0 + e.code_phase_chips;
          const double code_err =
              std::remainder(chips - (sig.code_chips(t_end) - spec.code0_chips + start_phase), 1023.0);
          sum_code2 += code_err * code_err;
          const double dop_err = e.carrier_doppler_hz - sig.doppler_hz(t_end - 0.5 * e.integration_s);
          sum_dop2 += dop_err * dop_err;
          ++n_err;
          r.mean_abs_very_early += std::abs(e.very_early);
          r.mean_abs_very_late += std::abs(e.very_late);
          r.mean_abs_prompt += std::abs(e.prompt);
        }
        r.last = e;
      }
    }
  }
  r.code_error_rms_chips = n_err ? std::sqrt(sum_code2 / n_err) : 1e9;
  r.doppler_error_rms_hz = n_err ? std::sqrt(sum_dop2 / n_err) : 1e9;
  if (n_err) {
    r.mean_abs_very_early /= n_err;
    r.mean_abs_very_late /= n_err;
    r.mean_abs_prompt /= n_err;
  }
  r.cn0_dbhz = ch.cn0_dbhz();
  r.final_state = ch.state();
  return r;
}

TEST(TrackingChannel, PullsInAndTracksAt45DbHz) {
  // Doppler 2000 Hz rising at 1 Hz/s; acquisition off by 200 Hz and 0.3 chip.
  ChannelSignalSpec spec;
  const RunResult r = track(spec, 3.0, 200.0, 0.3);
  EXPECT_GT(r.pll_lock_time_s, 0.0);
  EXPECT_LT(r.pll_lock_time_s, 0.5);
  EXPECT_GT(r.bit_sync_time_s, 0.0);
  EXPECT_LT(r.bit_sync_time_s, 2.0);
  EXPECT_EQ(r.final_state, ChannelState::tracking);
  EXPECT_LT(r.code_error_rms_chips, 0.05);
  EXPECT_LT(r.doppler_error_rms_hz, 2.0);
  EXPECT_NEAR(r.cn0_dbhz, 45.0, 1.5);
  // The last epoch: 10 ms on a bit edge, every flag up, C/N0 carried in the epoch.
  EXPECT_NEAR(r.last.integration_s, 0.010, 1e-5);
  EXPECT_TRUE(r.last.pll_lock);
  EXPECT_TRUE(r.last.code_lock);
  EXPECT_TRUE(r.last.bit_synced);
  EXPECT_NEAR(r.last.cn0_dbhz, 45.0, 1.5);
  EXPECT_EQ(r.last.prn, 5);
}

TEST(TrackingChannel, EstimatesCn0At35DbHz) {
  ChannelSignalSpec spec;
  spec.cn0_dbhz = 35.0;
  spec.seed = 21;
  const RunResult r = track(spec, 3.0, 50.0, 0.1);
  EXPECT_EQ(r.final_state, ChannelState::tracking);
  EXPECT_NEAR(r.cn0_dbhz, 35.0, 1.5);
}

TEST(TrackingChannel, KeepsTrackingThroughAFadeTo30DbHz) {
  ChannelSignalSpec spec;
  spec.seed = 9;
  spec.fade_at_s = 1.5;
  spec.cn0_after_dbhz = 30.0;
  const RunResult r = track(spec, 4.0, 50.0, 0.1);
  EXPECT_EQ(r.final_state, ChannelState::tracking);
  EXPECT_TRUE(r.last.pll_lock);
  EXPECT_LT(r.code_error_rms_chips, 0.05);
  EXPECT_LT(r.doppler_error_rms_hz, 2.0);
  EXPECT_NEAR(r.cn0_dbhz, 30.0, 1.5);
}

TEST(TrackingChannel, ReportsLossOfLockWhenTheSignalFadesTo15DbHz) {
  ChannelSignalSpec spec;
  spec.seed = 10;
  spec.fade_at_s = 1.5;
  spec.cn0_after_dbhz = 15.0;
  const RunResult r = track(spec, 4.0, 50.0, 0.1);
  EXPECT_EQ(r.final_state, ChannelState::lost);
  EXPECT_FALSE(r.last.code_lock);
}

TEST(TrackingChannel, ReportsLossOfLockOnA15DbHzSignal) {
  ChannelSignalSpec spec;
  spec.cn0_dbhz = 15.0;
  const RunResult r = track(spec, 3.0, 0.0, 0.0);
  EXPECT_EQ(r.final_state, ChannelState::lost);
  EXPECT_FALSE(r.last.pll_lock);
}

TEST(TrackingChannel, VeryEarlyAndVeryLateAreSymmetricAroundTheTrackedPeak) {
  ChannelSignalSpec spec;
  spec.seed = 4;
  TrackingConfig cfg;
  cfg.very_spacing_chips = 1.0;
  const RunResult r = track(spec, 2.0, 20.0, 0.0, cfg);
  // Triangle at +-0.5 chip: half the prompt amplitude on both sides.
  EXPECT_NEAR(r.mean_abs_very_early / r.mean_abs_prompt, 0.5, 0.05);
  EXPECT_NEAR(r.mean_abs_very_late / r.mean_abs_prompt, 0.5, 0.05);
}

TEST(TrackingChannel, PhaseCorrectionsMoveTheNcosOnce) {
  TrackingConfig cfg;
  cfg.sample_rate_hz = 2.046e6;
  TrackingChannel ch(cfg, ChannelStart{3, 1000.0, 1022.75, 100, 0, std::nullopt});
  NcoCommand cmd;
  cmd.code_rate_cps = 1.023e6;
  cmd.carrier_doppler_hz = 1000.0;
  cmd.code_phase_correction_chips = 0.5;
  cmd.carrier_phase_correction_cycles = 0.25;
  const double before = ch.code_chips_at(100);
  ch.apply(cmd);
  EXPECT_NEAR(ch.code_chips_at(100) - before, 0.5, 1e-12);  // continuous across the period wrap
  EXPECT_NEAR(ch.carrier_phase_cycles(), 0.25, 1e-12);
  SampleBlock b;
  b.first_sample_index = 100;
  b.samples.assign(2046, Sample{0, 0});
  std::vector<CorrelatorEpoch> out;
  ch.process(b, out);
  // 1 ms of NCO at the commanded rates, no second correction.
  EXPECT_NEAR(ch.code_chips_at(2146) - before, 0.5 + 1023.0, 1e-6);
  EXPECT_NEAR(ch.carrier_phase_cycles(), 0.25 + 1.0, 1e-9);
}

TEST(TrackingChannel, BadSettingsAreRejected) {
  TrackingConfig cfg;
  cfg.coherent_ms_after_bit_sync = 3;
  EXPECT_THROW(TrackingChannel(cfg, ChannelStart{3, 0.0, 0.0, 0, 0, std::nullopt}), std::invalid_argument);
  cfg.coherent_ms_after_bit_sync = 10;
  EXPECT_THROW(TrackingChannel(cfg, ChannelStart{33, 0.0, 0.0, 0, 0, std::nullopt}), std::invalid_argument);
  cfg.sample_rate_hz = 0.0;
  EXPECT_THROW(TrackingChannel(cfg, ChannelStart{3, 0.0, 0.0, 0, 0, std::nullopt}), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
