#include "receiver/tracking_channel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "receiver/correlator.hpp"
#include "receiver/tracking_loops.hpp"
#include "signals/gaussian_noise.hpp"
#include "signals/gps_constants.hpp"
#include "signals/satellite_signal_kernel.hpp"

namespace deepnav {
namespace {

// 2.5 Msps: not a multiple of the chip rate. At exactly 2.046 Msps the samples fall on the
// same chip fractions every period and the early-late discriminator has a dead zone of
// about a quarter chip when the code Doppler is small.
constexpr double kFs = 2.5e6;

/// A C/A signal with a Doppler ramp and random data bits in white noise (N0 = 1),
/// generated 1 ms at a time; `code_chips(t)` is its unwrapped code phase.
struct TestSignal {
  int prn = 5;
  double cn0_dbhz = 45.0;
  double doppler0_hz = 2000.0;
  double doppler_rate_hzps = 1.0;
  double code0_chips = 100.3;
  std::uint64_t seed = 3;

  double doppler(double t) const { return doppler0_hz + doppler_rate_hzps * t; }
  double code_chips(double t) const {
    // code rate = 1.023e6 (1 + fd / f_L1): integrate the Doppler ramp.
    const double k = gps::kCodeRate_cps / gps::kL1_Hz;
    return code0_chips + gps::kCodeRate_cps * t + k * (doppler0_hz * t + 0.5 * doppler_rate_hzps * t * t);
  }
  double carrier_cycles(double t) const { return doppler0_hz * t + 0.5 * doppler_rate_hzps * t * t + 0.3; }

  std::vector<Sample> generate(double seconds) const {
    const int per_ms = static_cast<int>(kFs / 1000);
    const int ms = static_cast<int>(seconds * 1000);
    const std::size_t total = static_cast<std::size_t>(per_ms) * static_cast<std::size_t>(ms);
    std::vector<float> i(total), q(total), scratch(static_cast<std::size_t>(per_ms));
    const float a = static_cast<float>(std::pow(10.0, cn0_dbhz / 20.0));
    for (int m = 0; m < ms; ++m) {
      const double t0 = m * 1e-3, t1 = (m + 1) * 1e-3;
      const double c0 = code_chips(t0), c1 = code_chips(t1);
      // Split at the code period edge; the data bit changes on 20-period boundaries.
      int first = 0;
      while (first < per_ms) {
        const double step = (c1 - c0) / per_ms;
        const double chips = c0 + first * step;
        const double period = std::floor(chips / 1023.0);
        const int last = std::min(per_ms, static_cast<int>(std::ceil(((period + 1) * 1023.0 - c0) / step)));
        const int count = std::max(1, last - first);
        std::mt19937_64 bit_rng(seed * 1000003 + static_cast<std::uint64_t>(period) / 20);
        const float sign = (bit_rng() & 1) ? -1.0f : 1.0f;
        SignalSegment sg;
        sg.code_phase_chips = chips - period * 1023.0;
        sg.code_step_chips = step;
        sg.carrier_phase_cycles = carrier_cycles(t0) + first * (carrier_cycles(t1) - carrier_cycles(t0)) / per_ms;
        sg.carrier_step_cycles = (carrier_cycles(t1) - carrier_cycles(t0)) / per_ms;
        sg.amplitude = a * sign;
        add_satellite_segment(i.data() + static_cast<std::size_t>(m) * per_ms + first,
                              q.data() + static_cast<std::size_t>(m) * per_ms + first, count, sg, ca_code_chips(prn),
                              scratch.data());
        first += count;
      }
    }
    GaussianNoise noise(seed + 17);
    const float sigma = static_cast<float>(std::sqrt(kFs / 2.0));
    noise.add_real(i, sigma);
    noise.add_real(q, sigma);
    const float scale = 64.0f / sigma;  // int16 with the noise at 64 counts RMS
    std::vector<Sample> out(i.size());
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] = {static_cast<std::int16_t>(std::lround(i[k] * scale)), static_cast<std::int16_t>(std::lround(q[k] * scale))};
    return out;
  }
};

struct RunResult {
  double code_error_rms_chips = 0.0;
  double doppler_error_rms_hz = 0.0;
  double cn0_dbhz = 0.0;
  bool bit_synced = false;
  double pll_lock_time_s = -1.0;
  ChannelState final_state = ChannelState::pull_in;
};

/// Tracks `seconds` of `sig`, starting with the given initial errors, in blocks of an odd size.
RunResult track(const TestSignal& sig, double seconds, double doppler_error_hz, double code_error_chips) {
  const auto samples = sig.generate(seconds);
  TrackingConfig cfg;
  cfg.sample_rate_hz = kFs;
  ChannelStart start{sig.prn, sig.doppler0_hz + doppler_error_hz, std::fmod(sig.code0_chips + code_error_chips, 1023.0), 0};
  TrackingChannel ch(cfg, start);
  LoopBandwidths bw;
  ScalarLoopController loop(start.doppler_hz, bw);
  RunResult r;
  double sum_code2 = 0.0, sum_dop2 = 0.0;
  int n_err = 0;
  const std::size_t block = 3001;
  std::vector<CorrelatorEpoch> epochs;
  for (std::size_t first = 0; first < samples.size(); first += block) {
    SampleBlock b;
    b.first_sample_index = static_cast<std::int64_t>(first);
    b.samples.assign(samples.begin() + static_cast<std::ptrdiff_t>(first),
                     samples.begin() + static_cast<std::ptrdiff_t>(std::min(samples.size(), first + block)));
    epochs.clear();
    ch.process(b, epochs);
    for (const auto& e : epochs) {
      ch.monitor(e);
      if (ch.state() == ChannelState::tracking) {
        LoopBandwidths narrow = bw;
        narrow.pll_hz = 10.0;
        loop.set_bandwidths(narrow);
      }
      ch.apply(loop.update(e, ch.state() == ChannelState::pull_in));
      if (r.pll_lock_time_s < 0 && ch.phase_locked()) r.pll_lock_time_s = ch.seconds_tracked();
      const double t_end = static_cast<double>(e.first_sample + e.samples) / kFs;
      if (t_end > 1.0) {
        const double code_err = ch.code_chips_at(e.first_sample + e.samples) - (sig.code_chips(t_end) - sig.code0_chips + start.code_phase_chips - code_error_chips);
        double wrapped = std::remainder(code_err, 1023.0);
        sum_code2 += wrapped * wrapped;
        const double dop_err = e.carrier_doppler_hz - sig.doppler(t_end - 0.5 * e.integration_s);
        sum_dop2 += dop_err * dop_err;
        ++n_err;
      }
    }
  }
  r.code_error_rms_chips = n_err ? std::sqrt(sum_code2 / n_err) : 1e9;
  r.doppler_error_rms_hz = n_err ? std::sqrt(sum_dop2 / n_err) : 1e9;
  r.cn0_dbhz = ch.cn0_dbhz();
  r.bit_synced = ch.bit_edge_period().has_value();
  r.final_state = ch.state();
  return r;
}

TEST(TrackingChannel, PullsInAndTracksAt45DbHz) {
  TestSignal sig;
  const RunResult r = track(sig, 3.0, 200.0, 0.3);
  EXPECT_GT(r.pll_lock_time_s, 0.0);
  EXPECT_LT(r.pll_lock_time_s, 0.6);
  EXPECT_TRUE(r.bit_synced);
  EXPECT_EQ(r.final_state, ChannelState::tracking);
  EXPECT_LT(r.code_error_rms_chips, 0.05);
  EXPECT_LT(r.doppler_error_rms_hz, 2.0);
  EXPECT_NEAR(r.cn0_dbhz, 45.0, 1.5);
}

TEST(TrackingChannel, TracksAt30DbHzAndEstimatesCn0) {
  TestSignal sig;
  sig.cn0_dbhz = 32.0;
  sig.seed = 9;
  const RunResult r = track(sig, 4.0, 50.0, 0.1);
  EXPECT_NE(r.final_state, ChannelState::lost);
  EXPECT_LT(r.code_error_rms_chips, 0.15);
  EXPECT_NEAR(r.cn0_dbhz, 32.0, 1.5);
}

TEST(TrackingChannel, ReportsLossOfLockWithoutSignal) {
  TestSignal sig;
  sig.cn0_dbhz = 10.0;
  const RunResult r = track(sig, 3.0, 0.0, 0.0);
  EXPECT_EQ(r.final_state, ChannelState::lost);
}

}  // namespace
}  // namespace deepnav
