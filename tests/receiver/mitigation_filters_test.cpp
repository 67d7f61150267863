// Interference mitigation through the SampleSource decorator: CW and chirp removed by
// excision and by the adaptive notch with the satellite's correlation kept, pulses
// blanked with clean samples untouched, and bad settings rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "mitigation_test_signal.hpp"
#include "receiver/mitigation/mitigation_blanking.hpp"
#include "receiver/mitigation/mitigation_excision.hpp"
#include "receiver/mitigation/mitigation_sample_source.hpp"

namespace deepnav {
namespace {

using test::kFs;

constexpr std::size_t kSamples = 4092 * 300;  // 300 ms: 300 correlations of 1 ms
constexpr double kCwOffsetHz = 151.7e3;

JammerConfig cw(double js_db) {
  JammerConfig j;
  j.type = JammerType::cw;
  j.js_db = js_db;
  j.center_offset_hz = kCwOffsetHz;
  return j;
}

/// The signal through the decorator with the given mitigation, by absolute index.
std::vector<Sample> mitigate(std::vector<Sample> in, MitigationMode mode, float* gain = nullptr,
                             MitigationConfig c = {}) {
  const std::size_t n = in.size();
  test::VectorSampleSource source(std::move(in), 10000);
  c.mode = mode;
  MitigationSampleSource m(source, c);
  auto out = test::drain(m, n, 7000).by_index;
  if (gain) *gain = m.output_gain();
  return out;
}

TEST(Mitigation, ExcisionRemovesA40DbCwAndKeepsTheCorrelationPeak) {
  const auto clean = test::test_samples(kSamples, std::nullopt);
  const auto jammed = test::test_samples(kSamples, cw(40.0));
  const double snr_clean = test::correlation_snr_db(clean);
  const double snr_jammed = test::correlation_snr_db(jammed);
  float gain = 0.0f;
  const auto excised = mitigate(jammed, MitigationMode::excision, &gain);
  const double snr_excised = test::correlation_snr_db(excised);
  // Tone power before and after, in input units (the output carries the decorator's gain).
  const double tone_in = test::tone_power(jammed, kCwOffsetHz);
  const double tone_out = test::tone_power(excised, kCwOffsetHz) / (gain * gain);
  const double noise_power = 2.0 * 64.0 * 64.0;
  RecordProperty("snr_clean_db", std::to_string(snr_clean));
  RecordProperty("snr_jammed_db", std::to_string(snr_jammed));
  RecordProperty("snr_excised_db", std::to_string(snr_excised));
  RecordProperty("cw_suppression_db", std::to_string(10 * std::log10(tone_in / tone_out)));
  EXPECT_NEAR(snr_clean, 15.0, 1.5);        // 45 dB-Hz over 1 ms
  EXPECT_LT(snr_jammed, snr_clean - 10.0);  // the CW costs far more than 10 dB unmitigated
  EXPECT_GT(snr_excised, snr_clean - 1.0);  // within 1 dB of the clean peak after excision
  // Stated residual: the CW, 19 dB above the noise power in the band, is left at least
  // 20 dB below it (suppressed by more than 39 dB).
  EXPECT_LT(tone_out, noise_power * 0.01);
  EXPECT_GT(10 * std::log10(tone_in / tone_out), 39.0);
}

TEST(Mitigation, NotchRemovesA40DbCwAndKeepsTheCorrelationPeak) {
  const auto clean = test::test_samples(kSamples, std::nullopt);
  const auto jammed = test::test_samples(kSamples, cw(40.0));
  float gain = 0.0f;
  const auto notched = mitigate(jammed, MitigationMode::notch, &gain);
  // Skip the first 10 ms: the notch converges from z0 = 0.
  const std::size_t settle = 4092 * 10;
  const double snr_clean = test::correlation_snr_db(clean, settle);
  const double snr_notched = test::correlation_snr_db(notched, settle);
  const double tone_out = test::tone_power(notched, kCwOffsetHz, settle) / (gain * gain);
  RecordProperty("snr_notched_db", std::to_string(snr_notched));
  EXPECT_GT(snr_notched, snr_clean - 1.5);
  EXPECT_LT(tone_out, 2.0 * 64.0 * 64.0 * 0.01);
}

TEST(Mitigation, ExcisionAndNotchCostLittleWithoutJammer) {
  const auto clean = test::test_samples(kSamples, std::nullopt);
  const double snr_clean = test::correlation_snr_db(clean);
  EXPECT_GT(test::correlation_snr_db(mitigate(clean, MitigationMode::excision)), snr_clean - 0.3);
  EXPECT_GT(test::correlation_snr_db(mitigate(clean, MitigationMode::notch)), snr_clean - 0.5);
  EXPECT_GT(test::correlation_snr_db(mitigate(clean, MitigationMode::automatic)), snr_clean - 0.3);
}

TEST(Mitigation, ExcisionOfNoiseOnlyRebuildsTheInput) {
  // Without anything to excise, overlapping Hann frames sum back to the input exactly:
  // only the level control's gain (constant over each 64-sample window) and int16
  // rounding remain. Per window, out = g in with a residual far below the signal.
  const auto clean = test::test_samples(4092 * 20, std::nullopt);
  float gain = 0.0f;
  const auto out = mitigate(clean, MitigationMode::excision, &gain);
  ASSERT_GT(gain, 1.0f);
  double residual = 0.0, total = 0.0;
  for (std::size_t k0 = 0; k0 + 64 <= clean.size(); k0 += 64) {
    std::complex<double> num = 0.0;
    double den = 0.0;
    for (std::size_t k = k0; k < k0 + 64; ++k) {
      const std::complex<double> x(clean[k].real(), clean[k].imag()), y(out[k].real(), out[k].imag());
      num += y * std::conj(x);
      den += std::norm(x);
    }
    const std::complex<double> g = num / den;
    for (std::size_t k = k0; k < k0 + 64; ++k) {
      const std::complex<double> x(clean[k].real(), clean[k].imag()), y(out[k].real(), out[k].imag());
      residual += std::norm(y - g * x);
      total += std::norm(y);
    }
  }
  // Rounding alone is -75 dB; an odd excised noise bin (probability 1e-7) stays near it.
  EXPECT_LT(10 * std::log10(residual / total), -60.0);
}

TEST(Mitigation, ExcisionFollowsASlowChirp) {
  JammerConfig chirp;
  chirp.type = JammerType::chirp;
  chirp.js_db = 40.0;
  chirp.center_offset_hz = 0.0;
  chirp.bandwidth_hz = 1.0e6;
  chirp.sweep_period_s = 1e-3;  // 1 MHz per ms: 125 kHz (16 bins) per 512-sample frame
  const auto clean = test::test_samples(kSamples, std::nullopt);
  const auto jammed = test::test_samples(kSamples, chirp);
  const double snr_clean = test::correlation_snr_db(clean);
  const double snr_jammed = test::correlation_snr_db(jammed);
  const double snr_excised = test::correlation_snr_db(mitigate(jammed, MitigationMode::excision));
  RecordProperty("snr_chirp_jammed_db", std::to_string(snr_jammed));
  RecordProperty("snr_chirp_excised_db", std::to_string(snr_excised));
  EXPECT_LT(snr_jammed, snr_clean - 10.0);
  EXPECT_GT(snr_excised, snr_clean - 3.0);
}

TEST(Mitigation, BlankingZeroesPulsesAndLeavesCleanSamplesUntouched) {
  JammerConfig pulsed;
  pulsed.type = JammerType::pulsed;
  pulsed.js_db = 50.0;
  pulsed.center_offset_hz = 300e3;
  pulsed.duty_cycle = 0.1;
  pulsed.pulse_rate_hz = 1000.0;
  const auto clean = test::test_samples(kSamples, std::nullopt);
  const auto jammed = test::test_samples(kSamples, pulsed);
  // At 13 dB noise alone crosses the threshold with probability 2e-9 per sample, so any
  // clean sample changed would be the blanker's fault (at the default 10 dB: 4.5e-5).
  MitigationConfig c;
  c.blanking_threshold_db = 13.0;
  const auto blanked = mitigate(jammed, MitigationMode::blanking, nullptr, c);
  const Jammer gate(pulsed, kFs, 0.0, test::kCn0Dbhz, 1);
  const std::size_t guard = static_cast<std::size_t>(MitigationConfig{}.blanking_guard_samples);
  std::size_t on = 0, on_zeroed = 0, off_far = 0, off_far_identical = 0;
  for (std::size_t k = 0; k < kSamples; ++k) {
    const bool is_on = gate.pulse_on(static_cast<std::int64_t>(k));
    if (is_on) {
      ++on;
      on_zeroed += blanked[k] == Sample(0, 0);
      continue;
    }
    bool near_pulse = false;  // within the guard (+1 for the pulse's first/last partial sample)
    for (std::size_t d = 1; d <= guard + 1 && !near_pulse; ++d)
      near_pulse = (k >= d && gate.pulse_on(static_cast<std::int64_t>(k - d))) ||
                   (k + d < kSamples && gate.pulse_on(static_cast<std::int64_t>(k + d)));
    if (near_pulse) continue;
    ++off_far;
    off_far_identical += blanked[k] == jammed[k];
  }
  EXPECT_NEAR(static_cast<double>(on) / kSamples, 0.1, 0.01);
  EXPECT_EQ(on_zeroed, on);               // every pulse sample is zeroed
  EXPECT_EQ(off_far_identical, off_far);  // every clean sample passes bit-exact
  // The correlation with pulses blanked loses about the duty cycle's 0.9 dB, not 20+ dB.
  const double snr_clean = test::correlation_snr_db(clean);
  EXPECT_LT(test::correlation_snr_db(jammed), snr_clean - 10.0);
  EXPECT_GT(test::correlation_snr_db(blanked), snr_clean - 2.0);
}

TEST(Mitigation, BlankingLeavesCleanNoiseAlone) {
  const auto clean = test::test_samples(kSamples, std::nullopt);
  test::VectorSampleSource source(clean, 10000);
  MitigationConfig c;
  c.mode = MitigationMode::blanking;
  MitigationSampleSource m(source, c);
  const auto out = test::drain(m, kSamples, 4096).by_index;
  // Noise alone crosses the 10 dB threshold with probability 4.5e-5 per sample, and each
  // crossing blanks 2 guard + 1 samples: about 4e-4 of the samples, all set to zero.
  std::size_t changed = 0, changed_to_zero = 0;
  for (std::size_t k = 0; k < kSamples; ++k) {
    changed += out[k] != clean[k];
    changed_to_zero += out[k] != clean[k] && out[k] == Sample(0, 0);
  }
  EXPECT_LT(static_cast<double>(changed) / kSamples, 1e-3);
  EXPECT_EQ(changed_to_zero, changed);
  EXPECT_EQ(m.stages().size(), 1u);
}

TEST(Mitigation, BadSettingsAreRejectedNamingTheField) {
  test::VectorSampleSource source({}, 1);
  const auto rejects = [&](MitigationConfig c, const std::string& field) {
    c.mode = MitigationMode::automatic;
    try {
      MitigationSampleSource m(source, c);
      ADD_FAILURE() << "accepted " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  MitigationConfig c;
  c.excision_fft_size = 500;
  rejects(c, "excision_fft_size");
  c = {};
  c.excision_fft_size = 32;
  rejects(c, "excision_fft_size");
  c = {};
  c.excision_threshold_db = 1.0;
  rejects(c, "excision_threshold_db");
  c = {};
  c.blanking_threshold_db = std::nan("");
  rejects(c, "blanking_threshold_db");
  c = {};
  c.blanking_guard_samples = -1;
  rejects(c, "blanking_guard_samples");
  c = {};
  c.notch_pole_radius = 1.0;
  rejects(c, "notch_pole_radius");
  c = {};
  c.notch_step = 0.0;
  rejects(c, "notch_step");
  try {
    parse_mitigation_mode("excise");
    ADD_FAILURE() << "accepted 'excise'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("none, notch, excision, blanking, auto"), std::string::npos) << e.what();
  }
  for (const auto& name : mitigation_mode_names()) EXPECT_EQ(to_string(parse_mitigation_mode(name)), name);
}

}  // namespace
}  // namespace deepnav
