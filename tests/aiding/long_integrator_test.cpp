// Long integration of a steered channel on a synthesized weak signal: the data-wiped
// coherent sum recovers the correlation gain of its length, the C/N0 estimator reads the
// signal's C/N0 from integrations of any length, and noise alone is not taken for a signal.
#include "aiding/long_integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <map>
#include <vector>

#include "aiding/data_wipeoff.hpp"
#include "aiding/integration_cn0_estimator.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "tests/receiver/channel_test_signal.hpp"

namespace deepnav::aiding {
namespace {

using deepnav::testing::ChannelSignal;
using deepnav::testing::ChannelSignalSpec;

/// Data bit k of the test signal (a fixed pseudo-random pattern).
int data_bit(std::int64_t k) { return ((k * 7919 + (k >> 3) * 104729) % 5) < 2 ? -1 : 1; }

/// The channel's 1 ms integrations of `seconds` of signal, its NCO held on the true Doppler
/// and code (what an ideal INS-steered replica does; the static signal needs no commands).
std::vector<CorrelatorEpoch> steered_epochs(double cn0_dbhz, double seconds, std::uint64_t seed) {
  ChannelSignalSpec spec;
  spec.fs_hz = 1.2e6;
  spec.cn0_dbhz = cn0_dbhz;
  spec.doppler_rate_hzps = 0.0;
  spec.code0_chips = 0.0;      // bits start at code period 0
  spec.carrier0_cycles = 0.0;  // and the replica's carrier phase is the signal's
  spec.seed = seed;
  spec.bit = data_bit;
  ChannelSignal sig(spec);
  TrackingConfig cfg;
  cfg.sample_rate_hz = spec.fs_hz;
  cfg.noise_on_every_period = true;
  TrackingChannel ch(cfg, ChannelStart{spec.prn, spec.doppler0_hz, 0.0, 0, 0, std::nullopt});
  ch.set_loss_detection(false);
  std::vector<CorrelatorEpoch> epochs;
  for (int ms = 0; ms < seconds * 1000.0; ms += 100) ch.process(sig.next(100), epochs);
  return epochs;
}

/// Post-integration SNR of complex sums of a constant signal: |mean|^2 / variance.
double snr(const std::vector<std::complex<double>>& v) {
  std::complex<double> mean = 0.0;
  for (const auto& x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double var = 0.0;
  for (const auto& x : v) var += std::norm(x - mean);
  var /= static_cast<double>(v.size() - 1);
  return std::norm(mean) / var;
}

/// Runs the epochs through a LongIntegrator whose signer gives each bit `sign_of(bit)`.
std::vector<SteeredIntegration> integrate(const std::vector<CorrelatorEpoch>& epochs, LongIntegrationConfig cfg,
                                          const std::function<int(std::int64_t)>& sign_of) {
  LongIntegrator li(cfg);
  std::vector<SteeredIntegration> out;
  const LongIntegrator::BitSigner signer = [&](std::int64_t start_period, const std::complex<double>&) {
    return sign_of(start_period / 20);
  };
  for (const CorrelatorEpoch& e : epochs) li.add(e, 0, signer, out);
  return out;
}

TEST(LongIntegration, DataWipedCoherentSumRecoversTheGainOfItsLength) {
  // 20 dB-Hz: a 20 ms bit has an SNR of 2 (3 dB), a 200 ms wiped integration 20 (13 dB).
  const std::vector<CorrelatorEpoch> epochs = steered_epochs(20.0, 12.0, 5);
  // Each bit's prompt (the channel's integrations never straddle a bit edge), data removed.
  std::map<std::int64_t, std::pair<std::complex<double>, int>> by_bit;
  for (const CorrelatorEpoch& e : epochs) {
    const int ms = static_cast<int>(std::lround(e.integration_s * 1e3));
    auto& [sum, count] = by_bit[(e.code_period - ms) / 20];
    sum += e.prompt;
    count += ms;
  }
  std::vector<std::complex<double>> bits;
  for (const auto& [bit, sum_ms] : by_bit)
    if (sum_ms.second == 20) bits.push_back(sum_ms.first * static_cast<double>(data_bit(bit)));
  LongIntegrationConfig cfg;
  cfg.coherent_ms = 200;
  const auto wiped = integrate(epochs, cfg, data_bit);
  std::vector<std::complex<double>> long_prompts;
  for (const auto& s : wiped) {
    ASSERT_TRUE(s.data_wiped);
    EXPECT_NEAR(s.sums.integration_s, 0.2, 1e-3);
    long_prompts.push_back(s.sums.prompt);
  }
  ASSERT_GE(long_prompts.size(), 55u);
  const double snr_bit = snr(bits), snr_long = snr(long_prompts);
  EXPECT_NEAR(10.0 * std::log10(snr_bit), 10.0 * std::log10(100.0 * 0.02), 0.7);
  EXPECT_NEAR(10.0 * std::log10(snr_long), 10.0 * std::log10(100.0 * 0.2), 1.5);
  // The gain of integrating ten bits coherently: 10 dB.
  EXPECT_NEAR(10.0 * std::log10(snr_long / snr_bit), 10.0, 1.5);

  // Wrong signs (a failed prediction): the coherent gain is gone.
  const auto wrong = integrate(epochs, cfg, [](std::int64_t k) { return data_bit(k * 31 + 7); });
  std::vector<std::complex<double>> wrong_prompts;
  for (const auto& s : wrong) wrong_prompts.push_back(s.sums.prompt);
  EXPECT_LT(snr(wrong_prompts), 0.3 * snr_long);
}

TEST(LongIntegration, UnpredictedBitsAreSummedInPowerAndEndACoherentRun) {
  const std::vector<CorrelatorEpoch> epochs = steered_epochs(30.0, 3.0, 6);
  LongIntegrationConfig cfg;
  cfg.coherent_ms = 200;
  cfg.noncoherent_ms = 400;
  // Bits 0-14 predicted, 15-49 not, from 50 on predicted again.
  const auto out = integrate(epochs, cfg, [](std::int64_t k) { return k >= 15 && k < 50 ? 0 : data_bit(k); });
  ASSERT_GE(out.size(), 4u);
  EXPECT_TRUE(out[0].data_wiped);
  EXPECT_NEAR(out[0].sums.integration_s, 0.2, 1e-3);
  EXPECT_TRUE(out[1].data_wiped);  // bits 10-14: the run ends where the prediction does
  EXPECT_NEAR(out[1].sums.integration_s, 0.1, 1e-3);
  EXPECT_FALSE(out[2].data_wiped);
  EXPECT_EQ(out[2].pieces, 20);
  EXPECT_NEAR(out[2].piece_s, 0.02, 1e-4);
  EXPECT_NEAR(out[2].sums.integration_s, 0.4, 1e-3);
  EXPECT_EQ(out[2].frequency_pairs, 19);
  // On the true frequency the averaged cross/dot discriminator reads about zero.
  EXPECT_NEAR(std::arg(out[2].frequency_product) / (2.0 * M_PI * 0.02), 0.0, 1.0);
  EXPECT_FALSE(out[3].data_wiped);
  EXPECT_EQ(out[3].pieces, 15);  // bits 35-49, then the wiped run starts again
  EXPECT_TRUE(out[4].data_wiped);
}

TEST(IntegrationCn0Estimator, ReadsTheC_N0FromWipedAndNonCoherentIntegrations) {
  for (const double cn0 : {12.0, 20.0}) {
    const std::vector<CorrelatorEpoch> epochs = steered_epochs(cn0, 12.0, 7);
    for (const int coherent_ms : {200, 20}) {
      LongIntegrationConfig cfg;
      cfg.coherent_ms = coherent_ms;  // 20: every bit unpredicted, summed in power
      cfg.noncoherent_ms = 1000;
      IntegrationCn0Estimator est(12.0, 5);  // the whole run: the estimate's scatter is small
      for (const auto& s : integrate(epochs, cfg, data_bit)) est.add(power_of(s, 1.2e6));
      ASSERT_TRUE(est.ready());
      // 12 s: +-0.2 dB of scatter for the wiped ones, +-0.7 dB for 20 ms bits at 12 dB-Hz.
      EXPECT_NEAR(est.cn0_dbhz(), cn0, coherent_ms == 200 ? 0.7 : 1.5) << coherent_ms << " ms at " << cn0 << " dB-Hz";
      EXPECT_TRUE(est.signal_detected(3.0));
      if (coherent_ms == 200) {
        EXPECT_GT(est.wiped_phase_lock_indicator(), 1.5);
      }
    }
  }
}

TEST(IntegrationCn0Estimator, NoiseAloneIsRarelyTakenForASignal) {
  const std::vector<CorrelatorEpoch> epochs = steered_epochs(-100.0, 30.0, 8);
  LongIntegrationConfig cfg;
  IntegrationCn0Estimator est;  // 2 s windows
  int windows = 0, detected = 0;
  for (const auto& s : integrate(epochs, cfg, data_bit)) {
    est.add(power_of(s, 1.2e6));
    if (!est.ready()) continue;
    ++windows;
    detected += est.signal_detected(3.0) ? 1 : 0;
  }
  ASSERT_GT(windows, 100);
  EXPECT_LE(detected, windows / 50);  // 3 sigmas: about 0.1 % of independent windows
  EXPECT_LT(est.wiped_phase_lock_indicator(), 1.5);
}

TEST(DataWipeoff, ABitIsJudgedAgainstTheWipedPhaseAndWithoutItCannotCondemnAPrediction) {
  DataWipeoff w;
  // Nothing learned: only the preambles are predicted (bits 0-7 of every subframe).
  const std::int64_t first = 300 * 1000;  // a subframe start
  EXPECT_EQ(w.wipe_sign(first, 1), -1);   // preamble bit 1 is sent as -1
  EXPECT_EQ(w.wipe_sign(first + 1, 1), 1);
  EXPECT_EQ(w.wipe_sign(first + 8, 1), 0);
  EXPECT_EQ(w.wipe_sign(first, -1), 1);  // an inverted channel
  // The carrier half a cycle off: with the wiped phase as reference the preamble agrees.
  const std::complex<double> turned = std::polar(1.0, M_PI);
  for (int b = 0; b < 8; ++b) {
    const int sent = w.wipe_sign(first + b, 1);
    const auto c = w.observe(first + b, turned * static_cast<double>(sent), turned, 1, 30.0);
    EXPECT_FALSE(c.disagreed) << b;
  }
  // Without a reference (the first bit of a wiped run after unpredicted bits) the in-phase
  // sign is the Costas loop's and may be half a cycle off: weighed as a bit wrong 40 % of
  // the time, such a bit moves the test by 0.22 where a disagreement at p = 1e-2 adds 3.9,
  // so one in every subframe, the rest agreeing against the wiped phase, raises no alarm.
  for (int sf = 1; sf <= 1000; ++sf)
    for (int b = 0; b < 8; ++b) {
      const std::int64_t bit = first + 300 * sf + b;
      const double sent = w.wipe_sign(bit, 1);
      const auto c = b == 0 ? w.observe(bit, turned * sent, std::nullopt, 1, 30.0)
                            : w.observe(bit, turned * sent, turned, 1, 30.0);
      EXPECT_EQ(c.disagreed, b == 0);
      ASSERT_FALSE(c.alarm) << sf;
    }
  // Referenced bits that do disagree (a wrong prediction) are found within a few bits.
  int alarm_after = -1;
  for (int b = 0; b < 8 && alarm_after < 0; ++b) {
    const std::int64_t bit = first + 300 * 2000 + b;
    if (w.observe(bit, -turned * static_cast<double>(w.wipe_sign(bit, 1)), turned, 1, 30.0).alarm) alarm_after = b + 1;
  }
  EXPECT_GT(alarm_after, 0);
  EXPECT_LE(alarm_after, 4);
}

}  // namespace
}  // namespace deepnav::aiding
