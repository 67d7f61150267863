#include "signals/sim/jammer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <vector>

#include "signals/sim/bandlimited_noise.hpp"
#include "signals/sim/tone_generator.hpp"

namespace deepnav {
namespace {

constexpr double kFs = 4.092e6;
constexpr double kIf = 1.0e6;
constexpr double kCn0Ref = 45.0;

using Block = std::vector<std::complex<float>>;

JammerConfig make(JammerType type, double js_db) {
  JammerConfig c;
  c.type = type;
  c.js_db = js_db;
  c.center_offset_hz = 200e3;
  c.bandwidth_hz = 1.0e6;
  c.sweep_period_s = 100e-6;
  c.duty_cycle = 0.3;
  c.pulse_rate_hz = 1000.0;
  return c;
}

Block run(const JammerConfig& c, std::size_t n, std::int64_t first = 0, std::uint64_t seed = 1) {
  Jammer jammer(c, kFs, kIf, kCn0Ref, seed);
  Block x(n);
  jammer.add_to(x, first);
  return x;
}

double expected_power(double js_db) { return std::pow(10.0, 0.1 * (kCn0Ref + js_db)); }

double power_db(const Block& x, const Jammer* gate = nullptr) {
  double p = 0;
  std::size_t on = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (gate && !gate->pulse_on(static_cast<std::int64_t>(k))) continue;
    p += std::norm(std::complex<double>(x[k]));
    ++on;
  }
  return 10.0 * std::log10(p / static_cast<double>(on));
}

/// Frequency (Hz) of the phase step between consecutive samples.
double step_frequency(const Block& x, std::size_t k) {
  return std::arg(std::complex<double>(x[k + 1]) * std::conj(std::complex<double>(x[k]))) * kFs / (2 * M_PI);
}

TEST(Jammer, PowerMatchesJsForEveryType) {
  for (JammerType type : {JammerType::cw, JammerType::chirp, JammerType::wideband, JammerType::pulsed}) {
    for (double js : {-10.0, 25.0, 60.0}) {
      JammerConfig c = make(type, js);
      Jammer gate(c, kFs, kIf, kCn0Ref, 1);
      const Block x = run(c, 1 << 17);
      EXPECT_NEAR(power_db(x, &gate), 10.0 * std::log10(expected_power(js)), 0.2) << to_string(type) << " " << js;
    }
  }
}

TEST(Jammer, CwSitsAtIfPlusOffset) {
  JammerConfig c = make(JammerType::cw, 30.0);
  c.center_offset_hz = -1234.5;
  const Block x = run(c, 100000, 123456789);
  // Unwrapped phase slope over the block.
  double total = 0;
  for (std::size_t k = 0; k + 1 < x.size(); ++k) total += step_frequency(x, k);
  EXPECT_NEAR(total / (x.size() - 1), kIf - 1234.5, 1e-3);
  // Absolute phase follows the sample index: compare with the exact phase at the last sample.
  const double n = 123456789.0 + 99999.0;
  const double cycles = std::fmod(n * (kIf - 1234.5) / kFs, 1.0);
  const double expected = std::remainder(2 * M_PI * cycles, 2 * M_PI);
  EXPECT_NEAR(std::remainder(std::arg(std::complex<double>(x.back())) - expected, 2 * M_PI), 0.0, 1e-4);
}

TEST(Jammer, ChirpSweepsItsBandWithTheRightPeriod) {
  JammerConfig c = make(JammerType::chirp, 20.0);
  c.center_offset_hz = 100e3;
  c.bandwidth_hz = 2.0e6;
  c.sweep_period_s = 250e-6;  // 1023 samples
  const Block x = run(c, 10000);
  const double f_low = kIf + 100e3 - 1.0e6, f_high = kIf + 100e3 + 1.0e6;
  const double slope_per_sample = c.bandwidth_hz / (c.sweep_period_s * kFs);
  double f_min = 1e12, f_max = -1e12;
  std::vector<std::size_t> resets;
  double previous = step_frequency(x, 0);
  for (std::size_t k = 1; k + 1 < x.size(); ++k) {
    // Frequencies above fs/2 alias; unwrap to the band around the chirp centre.
    double f = step_frequency(x, k);
    while (f < f_low - 0.25 * kFs) f += kFs;
    while (f > f_high + 0.25 * kFs) f -= kFs;
    f_min = std::min(f_min, f);
    f_max = std::max(f_max, f);
    if (f < previous - 0.5 * c.bandwidth_hz) resets.push_back(k);
    previous = f;
  }
  EXPECT_NEAR(f_min, f_low, 2 * slope_per_sample);
  EXPECT_NEAR(f_max, f_high, 2 * slope_per_sample);
  ASSERT_GE(resets.size(), 5u);
  for (std::size_t r = 1; r < resets.size(); ++r)
    EXPECT_NEAR(static_cast<double>(resets[r] - resets[r - 1]), c.sweep_period_s * kFs, 1.0);
}

/// Welch-style power spectral density at the given frequencies, computed with direct DFTs.
std::vector<double> band_psd(const Block& x, const std::vector<double>& freqs_hz) {
  constexpr std::size_t kSeg = 256;
  std::vector<double> psd(freqs_hz.size(), 0.0);
  for (std::size_t b = 0; b < freqs_hz.size(); ++b) {
    std::vector<std::complex<double>> twiddle(kSeg);
    for (std::size_t n = 0; n < kSeg; ++n) {
      const double hann = 0.5 - 0.5 * std::cos(2 * M_PI * static_cast<double>(n) / kSeg);
      twiddle[n] = hann * std::polar(1.0, -2 * M_PI * freqs_hz[b] * static_cast<double>(n) / kFs);
    }
    for (std::size_t s = 0; s + kSeg <= x.size(); s += kSeg) {
      std::complex<double> acc = 0;
      for (std::size_t n = 0; n < kSeg; ++n) acc += std::complex<double>(x[s + n]) * twiddle[n];
      psd[b] += std::norm(acc);
    }
  }
  return psd;
}

TEST(Jammer, WidebandNoiseIsFlatInBandAndSuppressedOutside) {
  JammerConfig c = make(JammerType::wideband, 40.0);
  c.center_offset_hz = 500e3;
  c.bandwidth_hz = 1.0e6;
  const Block x = run(c, 1 << 16);
  const double center = kIf + c.center_offset_hz;
  std::vector<double> in, out;
  for (double r = -0.35; r <= 0.351; r += 0.05) in.push_back(center + r * c.bandwidth_hz);
  for (double r : {-1.5, -1.0, -0.75, 0.75, 1.0, 1.5}) out.push_back(center + r * c.bandwidth_hz);
  const auto p_in = band_psd(x, in), p_out = band_psd(x, out);
  double mean_in = 0;
  for (double p : p_in) mean_in += p / static_cast<double>(p_in.size());
  for (std::size_t b = 0; b < p_in.size(); ++b)
    EXPECT_NEAR(10 * std::log10(p_in[b] / mean_in), 0.0, 1.0) << "in-band bin at " << in[b] << " Hz";
  for (std::size_t b = 0; b < p_out.size(); ++b)
    EXPECT_LT(10 * std::log10(p_out[b] / mean_in), -30.0) << "out-of-band bin at " << out[b] << " Hz";
}

TEST(Jammer, WidebandAtFullSampleRateIsWhite) {
  EXPECT_EQ(design_noise_shaping_taps(kFs, kFs).size(), 1u);
  JammerConfig c = make(JammerType::wideband, 10.0);
  c.bandwidth_hz = kFs;
  const Block x = run(c, 1 << 15);
  std::complex<double> lag1 = 0;
  double p = 0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    lag1 += std::complex<double>(x[k]) * std::conj(std::complex<double>(x[k - 1]));
    p += std::norm(std::complex<double>(x[k]));
  }
  EXPECT_LT(std::abs(lag1) / p, 0.03);
}

TEST(Jammer, PulsedOnFractionAndPeriod) {
  JammerConfig c = make(JammerType::pulsed, 30.0);
  c.duty_cycle = 0.3;
  c.pulse_rate_hz = 3000.0;  // 1364 samples per period
  for (double bw : {0.0, 500e3}) {
    c.bandwidth_hz = bw;
    const Block x = run(c, 1364 * 146);  // whole periods
    std::size_t on = 0;
    std::vector<std::size_t> rises;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const bool now = x[k] != std::complex<float>{};
      on += now;
      if (now && (k == 0 || x[k - 1] == std::complex<float>{})) rises.push_back(k);
    }
    EXPECT_NEAR(static_cast<double>(on) / x.size(), 0.3, 1e-3) << "bandwidth " << bw;
    ASSERT_GE(rises.size(), 100u);
    for (std::size_t r = 1; r < rises.size(); ++r)
      EXPECT_NEAR(static_cast<double>(rises[r] - rises[r - 1]), kFs / 3000.0, 1.0);
  }
}

TEST(Jammer, OutputDoesNotDependOnBlockBoundaries) {
  for (JammerType type : {JammerType::cw, JammerType::chirp, JammerType::wideband, JammerType::pulsed}) {
    JammerConfig c = make(type, 30.0);
    c.bandwidth_hz = type == JammerType::pulsed ? 300e3 : 1e6;
    const std::int64_t first = 4092 * 1000 + 7;
    const Block whole = run(c, 20000, first, 42);
    Jammer jammer(c, kFs, kIf, kCn0Ref, 42);
    Block pieces(whole.size());
    const std::size_t cuts[] = {0, 1, 1000, 1001, 4093, 12000, 20000};
    for (int k = 0; k + 1 < 7; ++k)
      jammer.add_to(std::span(pieces).subspan(cuts[k], cuts[k + 1] - cuts[k]),
                    first + static_cast<std::int64_t>(cuts[k]));
    for (std::size_t k = 0; k < whole.size(); ++k) ASSERT_EQ(whole[k], pieces[k]) << to_string(type) << " sample " << k;
  }
}

TEST(Jammer, OnlyBetweenStartAndEnd) {
  JammerConfig c = make(JammerType::cw, 0.0);
  c.start_s = 1e-3;
  c.end_s = 2e-3;
  const Block x = run(c, 12276);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const bool expect_on = k >= 4092 && k < 8184;
    ASSERT_EQ(x[k] != std::complex<float>{}, expect_on) << "sample " << k;
  }
}

TEST(Jammer, SameSeedSameNoiseOtherSeedOtherNoise) {
  const JammerConfig c = make(JammerType::wideband, 0.0);
  EXPECT_EQ(run(c, 1000, 0, 5), run(c, 1000, 0, 5));
  EXPECT_NE(run(c, 1000, 0, 5), run(c, 1000, 0, 6));
}

void expect_rejected(JammerConfig c, const std::string& field, double fs = kFs) {
  try {
    validate_jammer(c, fs, kIf);
    ADD_FAILURE() << "accepted a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(Jammer, ValidationNamesTheField) {
  JammerConfig c = make(JammerType::cw, 0.0);
  EXPECT_NO_THROW(validate_jammer(c, kFs, kIf));
  c.js_db = 121;
  expect_rejected(c, "js_db");
  c.js_db = -51;
  expect_rejected(c, "js_db");
  c = make(JammerType::cw, 0.0);
  c.center_offset_hz = 0.6 * kFs;
  expect_rejected(c, "center_offset_hz");
  c = make(JammerType::wideband, 0.0);
  c.bandwidth_hz = 0.0;
  expect_rejected(c, "bandwidth_hz");
  c.bandwidth_hz = 1.1 * kFs;
  expect_rejected(c, "bandwidth_hz");
  c = make(JammerType::chirp, 0.0);
  c.sweep_period_s = 0.0;
  expect_rejected(c, "sweep_period_s");
  c = make(JammerType::pulsed, 0.0);
  c.duty_cycle = 0.0;
  expect_rejected(c, "duty_cycle");
  c.duty_cycle = 1.5;
  expect_rejected(c, "duty_cycle");
  c = make(JammerType::pulsed, 0.0);
  c.pulse_rate_hz = -1.0;
  expect_rejected(c, "pulse_rate_hz");
  c = make(JammerType::cw, 0.0);
  c.start_s = 2.0;
  c.end_s = 1.0;
  expect_rejected(c, "end_s");
  c = make(JammerType::cw, NAN);
  expect_rejected(c, "js_db");
  expect_rejected(make(JammerType::cw, 0.0), "sample rate", -1.0);
  EXPECT_THROW(Jammer(make(JammerType::cw, 200.0), kFs, kIf, kCn0Ref, 1), std::invalid_argument);
}

TEST(Jammer, TypeNamesRoundTrip) {
  for (JammerType type : {JammerType::cw, JammerType::chirp, JammerType::wideband, JammerType::pulsed})
    EXPECT_EQ(parse_jammer_type(to_string(type)), type);
  try {
    parse_jammer_type("barrage");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cw, chirp, wideband, pulsed"), std::string::npos);
  }
}

TEST(ToneGenerator, MixShiftsFrequencyLikeGenerate) {
  ToneGenerator tone(-300e3, kFs);
  Block a(5000), b(5000, {1.0f, 0.0f});
  tone.generate(a, 77, 1.0f);
  tone.mix(b, 77);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(std::abs(a[k] - b[k]), 0.0, 1e-6);
}

}  // namespace
}  // namespace deepnav
