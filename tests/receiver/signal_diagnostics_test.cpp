#include "receiver/acquisition/signal_diagnostics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

namespace deepnav {
namespace {

constexpr double kFs = 4.0e6;

/// Complex Gaussian noise through a windowed-sinc lowpass of two-sided width `band_hz`,
/// moved to `centre_hz`, scaled to an RMS of about 300 (`real`: the real part only).
std::vector<Sample> band_noise(double band_hz, double centre_hz, bool real, std::size_t n = 40000) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  const int half = 64;
  std::vector<double> taps;
  for (int k = -half; k <= half; ++k) {
    const double x = band_hz / kFs * k;
    const double sinc = k == 0 ? 1.0 : std::sin(M_PI * x) / (M_PI * x);
    taps.push_back(band_hz / kFs * sinc * (0.54 + 0.46 * std::cos(M_PI * k / half)));
  }
  std::vector<std::complex<double>> white(n + taps.size());
  for (auto& w : white) w = {g(rng), g(rng)};
  std::vector<Sample> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::complex<double> y = 0.0;
    for (std::size_t k = 0; k < taps.size(); ++k) y += taps[k] * white[i + k];
    y *= std::polar(1.0, 2.0 * M_PI * centre_hz / kFs * static_cast<double>(i)) * 300.0 / std::sqrt(band_hz / kFs);
    out[i] = Sample(static_cast<std::int16_t>(std::lround(y.real())),
                    real ? std::int16_t{0} : static_cast<std::int16_t>(std::lround(y.imag())));
  }
  return out;
}

TEST(SignalDiagnostics, LevelsOfTwoBitSamplesInAByteContainer) {
  // The values +-1 and +-3 equally often: 4 levels, power 5 against 127.5^2, none at full scale.
  std::vector<Sample> s;
  for (int k = 0; k < 1000; ++k) s.push_back(Sample(static_cast<std::int16_t>(k % 2 ? 1 : -3), k % 3 ? 3 : -1));
  const SampleLevels l = measure_levels(s, false, converted_value_range(SampleFormat::ibyte));
  EXPECT_EQ(l.samples, 1000u);
  EXPECT_EQ(l.levels_used, 4);
  EXPECT_NEAR(l.rms_i, std::sqrt(5.0), 1e-9);
  EXPECT_EQ(l.at_full_scale_fraction, 0.0);
  const double q_power = (1000.0 - 334.0) / 1000.0 * 9.0 + 334.0 / 1000.0;
  EXPECT_NEAR(l.power_dbfs, 10.0 * std::log10((5.0 + q_power) / 2.0 / (127.5 * 127.5)), 1e-9);
  EXPECT_NEAR(l.iq_power_ratio_db, 10.0 * std::log10(5.0 / q_power), 1e-9);
}

TEST(SignalDiagnostics, ValuesAtTheRailsCountAsFullScale) {
  std::vector<Sample> s(100, Sample(5, -5));
  for (int k = 0; k < 10; ++k) s[static_cast<std::size_t>(k)] = Sample(127, -128);
  const SampleLevels l = measure_levels(s, false, converted_value_range(SampleFormat::ibyte));
  EXPECT_NEAR(l.at_full_scale_fraction, 0.1, 1e-12);
  // An inverted spectrum turns -128 into 128: still at the rail.
  s[0] = Sample(0, 128);
  EXPECT_NEAR(measure_levels(s, false, converted_value_range(SampleFormat::ibyte)).at_full_scale_fraction, 0.095,
              1e-12);
}

TEST(SignalDiagnostics, EightBitPairsReadAsSixteenBitShowFewLowBytes) {
  // int8 I/Q pairs with 4-bit levels read as one little-endian int16: Q * 256 + (I & 0xff).
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> level(-8, 7);
  std::vector<Sample> s(5000);
  for (Sample& x : s) {
    const auto pair = [&] { return static_cast<std::int16_t>(level(rng) * 256 + (level(rng) & 0xff)); };
    x = Sample(pair(), pair());
  }
  const SampleLevels l = measure_levels(s, false, converted_value_range(SampleFormat::ishort));
  EXPECT_EQ(l.low_byte_levels, 16);
  EXPECT_GT(l.levels_used, 200);
}

TEST(SignalDiagnostics, BandOfComplexNoiseIsCentredWhereItWasPut) {
  for (double centre : {0.0, 1.0e6, -0.6e6}) {
    const SpectrumBand b = find_spectrum_band(band_noise(2.0e6, centre, false), kFs, false);
    ASSERT_TRUE(b.found) << centre;
    EXPECT_NEAR(b.centre_hz, centre, 2 * b.resolution_hz) << centre;
    EXPECT_NEAR(b.width_hz, 2.0e6, 0.15 * 2.0e6) << centre;
    EXPECT_GT(b.contrast_db, 10.0) << centre;
  }
}

TEST(SignalDiagnostics, BandAcrossHalfTheSampleRateWraps) {
  const SpectrumBand b = find_spectrum_band(band_noise(1.0e6, kFs / 2, false), kFs, false);
  ASSERT_TRUE(b.found);
  EXPECT_NEAR(std::abs(b.centre_hz), kFs / 2, 2 * b.resolution_hz);
  EXPECT_NEAR(b.width_hz, 1.0e6, 0.15e6);
}

TEST(SignalDiagnostics, BandOfRealSamplesIsOnThePositiveSide) {
  const SpectrumBand b = find_spectrum_band(band_noise(1.0e6, 1.2e6, true), kFs, true);
  ASSERT_TRUE(b.found);
  EXPECT_NEAR(b.centre_hz, 1.2e6, 2 * b.resolution_hz);
}

TEST(SignalDiagnostics, WhiteNoiseHasNoBand) {
  const SpectrumBand b = find_spectrum_band(band_noise(kFs, 0.0, false), kFs, false);
  EXPECT_FALSE(b.found);
  EXPECT_LT(b.contrast_db, 3.0);
  // Too few samples for a periodogram: no band either.
  EXPECT_FALSE(find_spectrum_band(band_noise(2.0e6, 0.0, false, 1000), kFs, false).found);
}

TEST(SignalDiagnostics, StrongestCorrelationIsTheNearestToItsThreshold) {
  std::vector<AcquisitionResult> r(3);
  r[0].prn = 1, r[0].statistic = 30, r[0].threshold = 40;
  r[1].prn = 2, r[1].statistic = 36, r[1].threshold = 40;
  r[2].prn = 3, r[2].statistic = 33, r[2].threshold = 30;
  EXPECT_EQ(strongest_correlation(r)->prn, 3);
  EXPECT_NEAR(threshold_ratio(r[1]), 0.9, 1e-12);
  EXPECT_FALSE(strongest_correlation({}).has_value());
}

}  // namespace
}  // namespace deepnav
