// The filter-guided search on synthetic signals: a weak signal offset from the prediction
// is found in the window with its offsets and C/N0, the channel it starts has the signal's
// code phase, bit edges and transmit time; noise alone is not found; a prediction too
// uncertain for a narrow window is refused.
#include "receiver/acquisition/guided_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "channel_test_signal.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

using testing::ChannelSignal;
using testing::ChannelSignalSpec;

constexpr double kFs = 2.5e6;
constexpr double kSignalStartSow = 345600.0;  // transmit time of the signal's code chip 0 (a bit edge)

ChannelSignalSpec weak_signal(double cn0_dbhz, std::uint64_t seed) {
  ChannelSignalSpec s;
  s.fs_hz = kFs;
  s.prn = 7;
  s.cn0_dbhz = cn0_dbhz;
  s.doppler0_hz = 1500.0;
  s.doppler_rate_hzps = 0.5;
  s.code0_chips = 300.7;
  s.seed = seed;
  return s;
}

double true_transmit_sow(const ChannelSignal& sig, double t) {
  return kSignalStartSow + sig.code_chips(t) / gps::kCodeRate_cps;
}

/// The prediction a filter would make, off by the given errors (signal minus prediction).
SignalPrediction predict(const ChannelSignal& sig, double code_error_chips, double doppler_error_hz) {
  SignalPrediction p;
  p.prn = sig.spec().prn;
  p.sample = 0;
  p.transmit_sow = true_transmit_sow(sig, 0.0) - code_error_chips / gps::kCodeRate_cps;
  p.doppler_hz = sig.doppler_hz(0.0) - doppler_error_hz;
  p.doppler_rate_hzps = sig.spec().doppler_rate_hzps;
  p.code_sigma_chips = 0.1;
  p.doppler_sigma_hz = 2.0;
  return p;
}

/// Feeds 10 ms blocks until the search ends; returns the samples fed.
std::int64_t run(GuidedSearch& search, ChannelSignal& sig) {
  std::int64_t end = 0;
  while (search.outcome() == GuidedSearch::Outcome::searching && end < static_cast<std::int64_t>(6 * kFs)) {
    const SampleBlock b = sig.next(10);
    search.add(b);
    end = b.first_sample_index + static_cast<std::int64_t>(b.samples.size());
  }
  return end;
}

TEST(GuidedSearch, FindsA17DbHzSignalOffTheCentreOfItsWindow) {
  ChannelSignal sig(weak_signal(17.0, 5));
  const double code_error = -0.6, doppler_error = 12.0;
  GuidedSearch search({}, predict(sig, code_error, doppler_error), kFs, 0.0);
  EXPECT_EQ(search.cells(), 3 * 15);  // 3 Doppler bins x 3 calls x 5 taps
  const std::int64_t end = run(search, sig);
  ASSERT_EQ(search.outcome(), GuidedSearch::Outcome::found) << "after " << end / kFs << " s";
  const GuidedDetection& d = *search.detection();
  EXPECT_NEAR(d.code_offset_chips, code_error, 0.1);
  EXPECT_NEAR(d.doppler_offset_hz, doppler_error, 5.0);
  EXPECT_NEAR(d.cn0_dbhz, 17.0, 2.0);
  EXPECT_LE(d.dwell_s, 4.0);
  EXPECT_GT(d.statistic, d.threshold);

  // The channel start: the signal's code phase and Doppler at that sample, code period 0's
  // transmit time a whole millisecond of the signal's, bit edges on its 20 ms boundaries.
  const GuidedStart start = search.start_at(end, 3);
  const double t = static_cast<double>(end) / kFs;
  EXPECT_EQ(start.channel.prn, 7);
  EXPECT_EQ(start.channel.channel, 3);
  EXPECT_EQ(start.channel.sample_index, end);
  EXPECT_NEAR(start.channel.doppler_hz, sig.doppler_hz(t), 5.0);
  const double true_phase = std::fmod(sig.code_chips(t), 1023.0);
  EXPECT_NEAR(std::remainder(start.channel.code_phase_chips - true_phase, 1023.0), 0.0, 0.1);
  const double period0_truth = true_transmit_sow(sig, t) - start.channel.code_phase_chips / gps::kCodeRate_cps;
  EXPECT_NEAR(start.period0_transmit_sow, period0_truth, 0.2 / gps::kCodeRate_cps);
  EXPECT_DOUBLE_EQ(std::round(start.period0_transmit_sow * 1e3), start.period0_transmit_sow * 1e3);
  ASSERT_TRUE(start.channel.bit_edge_period.has_value());
  const auto ms = std::llround(start.period0_transmit_sow * 1e3) + *start.channel.bit_edge_period;
  EXPECT_EQ(ms % 20, 0);
  EXPECT_LT(*start.channel.bit_edge_period, 20);
}

TEST(GuidedSearch, FindsA15DbHzSignalWithinItsLongestDwell) {
  // 20 ms pieces summed for up to 4 s: at 15 dB-Hz the cell's mean power sum stands about 7
  // sigma above noise alone at the last check, so nearly every search finds it.
  int found = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    ChannelSignal sig(weak_signal(15.0, seed));
    GuidedSearch search({}, predict(sig, 0.3, -7.0), kFs, 0.0);
    run(search, sig);
    if (search.outcome() != GuidedSearch::Outcome::found) continue;
    ++found;
    EXPECT_NEAR(search.detection()->code_offset_chips, 0.3, 0.15) << "seed " << seed;
    EXPECT_NEAR(search.detection()->cn0_dbhz, 15.0, 2.0) << "seed " << seed;
  }
  EXPECT_GE(found, 7);
}

TEST(GuidedSearch, NoiseAloneIsNotFound) {
  // Eight full-length searches (4 s each) on noise: none may report a signal. With the
  // default false-alarm probability (1e-4 per search) a detection here means a wrong threshold.
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    ChannelSignal sig(weak_signal(-100.0, seed));
    GuidedSearch search({}, predict(sig, 0.0, 0.0), kFs, 0.0);
    run(search, sig);
    EXPECT_EQ(search.outcome(), GuidedSearch::Outcome::not_found) << "seed " << seed;
    EXPECT_NEAR(search.dwell_s(), 4.0, 0.021) << "seed " << seed;
  }
}

TEST(GuidedSearch, AStrongSignalIsFoundAtTheFirstCheck) {
  ChannelSignal sig(weak_signal(40.0, 9));
  GuidedSearch search({}, predict(sig, 1.3, -25.0), kFs, 0.0);
  run(search, sig);
  ASSERT_EQ(search.outcome(), GuidedSearch::Outcome::found);
  EXPECT_NEAR(search.detection()->dwell_s, 1.0, 0.021);
  EXPECT_NEAR(search.detection()->code_offset_chips, 1.3, 0.1);
  EXPECT_NEAR(search.detection()->doppler_offset_hz, -25.0, 5.0);
}

TEST(GuidedSearch, LostSamplesDropOnlyThePiecesTheyCut) {
  // One 10 ms block in ten never arrives (a lossy stream): the pieces it cuts are dropped,
  // the others still add up, and the start is where the signal is.
  ChannelSignal sig(weak_signal(35.0, 11));
  GuidedSearch search({}, predict(sig, -0.8, 9.0), kFs, 0.0);
  std::int64_t end = 0;
  for (int block = 0; search.outcome() == GuidedSearch::Outcome::searching && block < 600; ++block) {
    const SampleBlock b = sig.next(10);
    end = b.first_sample_index + static_cast<std::int64_t>(b.samples.size());
    if (block % 10 != 5) search.add(b);
  }
  ASSERT_EQ(search.outcome(), GuidedSearch::Outcome::found);
  // 1 s of whole pieces needed about 1.25 s of samples (each gap cuts one or two bits).
  EXPECT_NEAR(search.detection()->dwell_s, 1.0, 0.021);
  EXPECT_GT(static_cast<double>(end) / kFs, 1.15);
  EXPECT_NEAR(search.detection()->code_offset_chips, -0.8, 0.1);
  const GuidedStart start = search.start_at(end, 0);
  const double true_phase = std::fmod(sig.code_chips(static_cast<double>(end) / kFs), 1023.0);
  EXPECT_NEAR(std::remainder(start.channel.code_phase_chips - true_phase, 1023.0), 0.0, 0.1);
}

TEST(GuidedSearch, AWideOrUncertainPredictionIsRefused) {
  ChannelSignal sig(weak_signal(40.0, 9));
  SignalPrediction p = predict(sig, 0.0, 0.0);
  EXPECT_TRUE(GuidedSearch::is_narrow({}, p));
  p.code_sigma_chips = 3.0;  // 4 sigma: 12 chips, beyond the 8-chip limit
  EXPECT_FALSE(GuidedSearch::is_narrow({}, p));
  EXPECT_THROW(GuidedSearch({}, p, kFs, 0.0), std::invalid_argument);
  p.code_sigma_chips = 0.1;
  p.doppler_sigma_hz = 80.0;
  EXPECT_FALSE(GuidedSearch::is_narrow({}, p));
  // A wider window that is still narrow gets more cells.
  p.doppler_sigma_hz = 2.0;
  p.code_sigma_chips = 1.0;  // 4 chips: 7 calls
  EXPECT_EQ(GuidedSearch({}, p, kFs, 0.0).cells(), 3 * 7 * 5);
}

TEST(GuidedSearch, AWeakDetectionNearAStrongSatellitesCodeLinesIsSuspect) {
  // 45 dB-Hz tracked at 1200 Hz; a 20 dB-Hz detection 3 kHz + 15 Hz away sits on a line.
  EXPECT_TRUE(cross_correlation_suspect(4215.0, 20.0, 1200.0, 45.0, 40.0, 18.0));
  EXPECT_TRUE(cross_correlation_suspect(-1830.0, 20.0, 1200.0, 45.0, 40.0, 18.0));  // -3 kHz + -30 Hz
  EXPECT_FALSE(cross_correlation_suspect(4700.0, 20.0, 1200.0, 45.0, 40.0, 18.0));  // between lines
  EXPECT_FALSE(cross_correlation_suspect(4215.0, 30.0, 1200.0, 45.0, 40.0, 18.0));  // too strong for it
}

TEST(GuidedSearch, ACrossCorrelationIsWhatTheSuspicionGuardsAgainst) {
  // A 50 dB-Hz PRN 7 signal, searched for as PRN 8 at a Doppler 1 kHz off PRN 7's (a code
  // line): the search finds PRN 7's cross-correlation (seeded: it does here), weak and on a
  // line, so the guard rejects it.
  ChannelSignal sig(weak_signal(50.0, 4));
  SignalPrediction p = predict(sig, 0.0, 0.0);
  p.prn = 8;
  p.doppler_hz += 1000.0;
  GuidedSearch search({}, p, kFs, 0.0);
  run(search, sig);
  ASSERT_EQ(search.outcome(), GuidedSearch::Outcome::found);
  const GuidedDetection& d = *search.detection();
  EXPECT_LT(d.cn0_dbhz, 50.0 - 18.0);
  EXPECT_TRUE(
      cross_correlation_suspect(p.doppler_hz + d.doppler_offset_hz, d.cn0_dbhz, sig.doppler_hz(0.0), 50.0, 40.0, 18.0));
}

}  // namespace
}  // namespace deepnav
