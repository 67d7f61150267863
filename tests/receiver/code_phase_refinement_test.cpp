#include "receiver/acquisition/code_phase_refinement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

struct ToneSpec {
  int prn = 7;
  double fs_hz = 2.6e6;  ///< not a multiple of the chip rate: the chip edges fall everywhere
  double if_hz = 0.0;
  double code_phase_chips = 321.37;  ///< at the first sample
  double doppler_hz = 1234.5;
  double cn0_dbhz = 45.0;
  double length_ms = 10.0;
  int bit_flip_ms = -1;  ///< the data bit changes sign at this millisecond (-1: never)
  std::uint64_t seed = 3;
};

/// A C/A signal with white noise at the C/N0 asked for, quantised to int16 with room for
/// the noise (sigma 200 per component).
std::vector<Sample> make_signal(const ToneSpec& t) {
  constexpr double kNoiseSigma = 200.0;
  // C/N0 = A^2 / (2 sigma^2 / fs) for a complex signal of amplitude A in complex noise of
  // variance 2 sigma^2 per sample.
  const double amplitude = std::sqrt(std::pow(10.0, t.cn0_dbhz / 10.0) * 2.0 * kNoiseSigma * kNoiseSigma / t.fs_hz);
  const auto n = static_cast<std::size_t>(t.length_ms * 1e-3 * t.fs_hz);
  const CaCodeChips& code = ca_code_chips(t.prn);
  const double chips_per_sample = gps::kCodeRate_cps * (1.0 + t.doppler_hz / gps::kL1_Hz) / t.fs_hz;
  std::mt19937_64 rng(t.seed);
  std::normal_distribution<double> noise(0.0, kNoiseSigma);
  std::vector<Sample> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double chip = std::fmod(t.code_phase_chips + static_cast<double>(k) * chips_per_sample, 1023.0);
    const double bit = (t.bit_flip_ms >= 0 && static_cast<double>(k) >= t.bit_flip_ms * 1e-3 * t.fs_hz) ? -1.0 : 1.0;
    const double phase = 2.0 * std::numbers::pi * (t.if_hz + t.doppler_hz) * static_cast<double>(k) / t.fs_hz + 0.4;
    const double a = amplitude * bit * code[static_cast<std::size_t>(chip)];
    out[k] = Sample(static_cast<std::int16_t>(std::lround(a * std::cos(phase) + noise(rng))),
                    static_cast<std::int16_t>(std::lround(a * std::sin(phase) + noise(rng))));
  }
  return out;
}

double chip_error(double a, double b) { return std::remainder(a - b, 1023.0); }

TEST(CodePhaseRefinement, FindsThePeakCentreAndDopplerFromTheAcquisitionsValues) {
  // A start 0.3 chip and 60 Hz off, as the acquisition's lag grid and bin leave them.
  for (const std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    ToneSpec t;
    t.seed = seed;
    const CodePhaseRefiner refiner(t.fs_hz, t.if_hz);
    const RefinedSignal r = refiner.refine(make_signal(t), t.prn, t.code_phase_chips + 0.3, t.doppler_hz - 60.0);
    ASSERT_TRUE(r.converged) << r.reason;
    // 45 dB-Hz over 10 ms: sqrt(0.5 / (2 C/N0 T)) = 0.028 chip of noise; 0.1 chip is 3.5 sigma.
    EXPECT_LT(std::abs(chip_error(r.code_phase_chips, t.code_phase_chips)), 0.1) << seed;
    EXPECT_NEAR(r.doppler_hz, t.doppler_hz, 25.0) << seed;
    EXPECT_GE(r.code_phase_chips, 0.0);
    EXPECT_LT(r.code_phase_chips, 1023.0);
  }
}

TEST(CodePhaseRefinement, IsUnbiasedOverManyNoiseDraws) {
  // The early-late balance finds the centre of a symmetric peak: averaged over draws and
  // over starts on either side, the error is the noise's alone.
  double sum = 0.0, sum_sq = 0.0;
  constexpr int kDraws = 16;
  for (int i = 0; i < kDraws; ++i) {
    ToneSpec t;
    t.seed = 100 + static_cast<std::uint64_t>(i);
    t.code_phase_chips = 17.0 + 61.3 * i;
    const CodePhaseRefiner refiner(t.fs_hz, t.if_hz);
    const double start_off = (i % 2 == 0 ? 0.35 : -0.35);
    const RefinedSignal r = refiner.refine(make_signal(t), t.prn, t.code_phase_chips + start_off, t.doppler_hz);
    ASSERT_TRUE(r.converged) << r.reason;
    const double e = chip_error(r.code_phase_chips, t.code_phase_chips);
    sum += e;
    sum_sq += e * e;
  }
  const double mean = sum / kDraws, rms = std::sqrt(sum_sq / kDraws);
  EXPECT_LT(std::abs(mean), 0.02);
  EXPECT_LT(rms, 0.05);
}

TEST(CodePhaseRefinement, ADataBitFlipInTheSnapshotLeavesTheDoppler) {
  ToneSpec t;
  t.bit_flip_ms = 4;
  t.if_hz = 0.6e6;
  const CodePhaseRefiner refiner(t.fs_hz, t.if_hz);
  const RefinedSignal r = refiner.refine(make_signal(t), t.prn, t.code_phase_chips - 0.2, t.doppler_hz + 90.0);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.doppler_hz, t.doppler_hz, 25.0);
  EXPECT_LT(std::abs(chip_error(r.code_phase_chips, t.code_phase_chips)), 0.1);
}

TEST(CodePhaseRefinement, ACodePhaseAcrossTheCodeEpochWraps) {
  ToneSpec t;
  t.code_phase_chips = 1022.9;
  const CodePhaseRefiner refiner(t.fs_hz, t.if_hz);
  const RefinedSignal r = refiner.refine(make_signal(t), t.prn, 0.15, t.doppler_hz);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_LT(std::abs(chip_error(r.code_phase_chips, t.code_phase_chips)), 0.1);
}

TEST(CodePhaseRefinement, BadInputIsAnError) {
  EXPECT_THROW(CodePhaseRefiner(0.5e6, 0.0), std::invalid_argument);
  EXPECT_THROW(CodePhaseRefiner(2.6e6, 1.4e6), std::invalid_argument);
  EXPECT_THROW(CodePhaseRefiner(2.6e6, 0.0, {1.2, 20, 2}), std::invalid_argument);
  const CodePhaseRefiner refiner(2.6e6, 0.0);
  ToneSpec t;
  t.length_ms = 0.5;
  EXPECT_THROW(refiner.refine(make_signal(t), t.prn, 0.0, 0.0), std::invalid_argument);
  t.length_ms = 2.0;
  EXPECT_THROW(refiner.refine(make_signal(t), 33, 0.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
