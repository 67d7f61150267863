#include "receiver/tracking/correlator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "converter_samples.hpp"
#include "signals/sim/satellite_signal_kernel.hpp"

namespace deepnav {
namespace {

/// n samples of PRN `prn` at code phase `code0` with amplitude `a` plus uniform int noise.
std::vector<Sample> make_signal(int prn, int n, double code0, double code_step, double carrier_step, float a,
                                std::uint64_t seed) {
  std::vector<float> i(static_cast<std::size_t>(n)), q(static_cast<std::size_t>(n)),
      scratch(static_cast<std::size_t>(n));
  SignalSegment sg;
  sg.code_phase_chips = code0;
  sg.code_step_chips = code_step;
  sg.carrier_phase_cycles = 0.37;
  sg.carrier_step_cycles = carrier_step;
  sg.amplitude = a;
  add_satellite_segment(i.data(), q.data(), n, sg, ca_code_chips(prn), scratch.data());
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> noise(-40, 40);
  std::vector<Sample> out(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = {static_cast<std::int16_t>(std::lround(i[k]) + noise(rng)),
              static_cast<std::int16_t>(std::lround(q[k]) + noise(rng))};
  return out;
}

/// A randomized span: sample rates 2.046-20 Msps (commensurate with the chip rate or not),
/// spacings 0.1-1 chip, VE/VL on or off, Doppler +-10 kHz on an IF up to fs/4, lengths
/// that are and are not multiples of the vector widths, inputs from 1 bit to full-scale
/// int16, with a strong PRN signal near the prompt so every tap has something to see.
struct RandomCase {
  CorrelatorSpan span;
  std::vector<Sample> x;
  int prn = 0;
};

RandomCase random_case(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  static const double kRates[] = {2.046e6, 4.092e6, 5.0e6, 8.184e6, 10.23e6, 16.368e6, 20.0e6};
  const double fs = u(rng) < 0.5 ? kRates[rng() % 7] : 2.046e6 + u(rng) * (20.0e6 - 2.046e6);
  RandomCase c;
  c.prn = 1 + static_cast<int>(rng() % 32);
  CorrelatorSpan& s = c.span;
  s.code_step_chips = 1.023e6 / fs * (1.0 + (u(rng) - 0.5) * 6e-6);
  const double if_hz = u(rng) < 0.3 ? 0.0 : u(rng) * fs / 4.0;
  s.carrier_step_cycles = (if_hz + (u(rng) - 0.5) * 20e3) / fs;
  s.carrier_phase_cycles = (u(rng) - 0.5) * 10.0;
  s.code_phase_chips = (u(rng) - 0.5) * 4000.0;
  s.spacing_chips = 0.1 + 0.9 * u(rng);
  s.very_spacing_chips = u(rng) < 0.5 ? 0.0 : s.spacing_chips + u(rng) * (2.0 - s.spacing_chips);

  // Input scale: 1 bit, 2 bits, 8 bits, 12 bits, full-scale 16 bits.
  const auto kind = static_cast<test_input::Converter>(rng() % test_input::kConverters);
  const double amp = test_input::converter_amplitude(kind);
  const auto& code = ca_code_chips(c.prn);
  const double lag = (u(rng) - 0.5) * 0.6;  // signal a little off the prompt
  c.x.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double chip = s.code_phase_chips + lag + k * s.code_step_chips;
    const double lvl = code[static_cast<std::size_t>(std::fmod(std::fmod(std::floor(chip), 1023.0) + 1023.0, 1023.0))];
    const double ph = 2.0 * M_PI * (s.carrier_phase_cycles + 0.1 + k * s.carrier_step_cycles);
    c.x[static_cast<std::size_t>(k)] =
        test_input::converter_sample(kind, amp * lvl * std::cos(ph), amp * lvl * std::sin(ph), rng);
  }
  if (kind == test_input::Converter::sixteen_bits && n > 2) {  // the extremes of int16 must not overflow anything
    c.x[0] = {-32768, 32767};
    c.x[static_cast<std::size_t>(n - 1)] = {32767, -32768};
  }
  return c;
}

constexpr int kLengths[] = {1, 7, 33, 1023, 4092, 5000};

TEST(Correlator, SimdKernelsAreBitExactWithThePortableKernel) {
  std::mt19937_64 rng(20261129);
  for (int trial = 0; trial < 240; ++trial) {
    const int n = kLengths[trial % 6] + (trial % 12 >= 6 ? static_cast<int>(rng() % 64) : 0);
    const RandomCase c = random_case(rng, n);
    const auto& code = ca_code_chips(c.prn);
    const auto& noise = ca_code_chips(c.prn % 32 + 1);
    const CorrelatorSums p = correlate(CorrelatorKernel::portable, c.x.data(), n, c.span, code, noise);
    for (CorrelatorKernel k : available_correlator_kernels()) {
      SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(k) << " trial " << trial << " n " << n);
      const CorrelatorSums s = correlate(k, c.x.data(), n, c.span, code, noise);
      EXPECT_EQ(s.early, p.early);
      EXPECT_EQ(s.prompt, p.prompt);
      EXPECT_EQ(s.late, p.late);
      EXPECT_EQ(s.very_early, p.very_early);
      EXPECT_EQ(s.very_late, p.very_late);
      EXPECT_EQ(s.noise, p.noise);
    }
  }
}

/// Every kernel the project has, whether or not this CPU can run it: one that cannot run here
/// is reported as skipped, not passed.
class EveryKernel : public testing::TestWithParam<CorrelatorKernel> {
 protected:
  void SetUp() override {
    const auto have = available_correlator_kernels();
    if (std::find(have.begin(), have.end(), GetParam()) == have.end())
      GTEST_SKIP() << "this CPU cannot run the " << correlator_kernel_name(GetParam())
                   << " kernel: its bit-exactness is not tested on this machine";
  }
};

TEST_P(EveryKernel, IsBitExactWithThePortableKernelWithAndWithoutTheNoiseTap) {
  // Every offset into the vector widths and code phase, every tap layout and input scale;
  // without the noise tap the other sums are the same and the noise sum is zero.
  const CorrelatorKernel k = GetParam();
  std::mt19937_64 rng(918273);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = kLengths[trial % 6] + static_cast<int>(rng() % 64);
    RandomCase c = random_case(rng, n);
    const auto& code = ca_code_chips(c.prn);
    const auto& noise = ca_code_chips(c.prn % 32 + 1);
    c.span.noise_tap = trial % 2 == 0;
    SCOPED_TRACE(testing::Message() << "trial " << trial << " n " << n << " noise tap " << c.span.noise_tap);
    const CorrelatorSums p = correlate(CorrelatorKernel::portable, c.x.data(), n, c.span, code, noise);
    const CorrelatorSums s = correlate(k, c.x.data(), n, c.span, code, noise);
    EXPECT_EQ(s.early, p.early);
    EXPECT_EQ(s.prompt, p.prompt);
    EXPECT_EQ(s.late, p.late);
    EXPECT_EQ(s.very_early, p.very_early);
    EXPECT_EQ(s.very_late, p.very_late);
    EXPECT_EQ(s.noise, p.noise);
    if (!c.span.noise_tap) {
      EXPECT_EQ(s.noise, std::complex<double>(0.0));
      c.span.noise_tap = true;
      const CorrelatorSums with = correlate(k, c.x.data(), n, c.span, code, noise);
      EXPECT_EQ(with.prompt, s.prompt);
      EXPECT_EQ(with.early, s.early);
      EXPECT_EQ(with.late, s.late);
    }
  }
}

TEST_P(EveryKernel, CanBeChosenForTheWholeProgram) {
  const CorrelatorKernel before = best_correlator_kernel();
  use_correlator_kernel(GetParam());
  EXPECT_EQ(best_correlator_kernel(), GetParam());
  EXPECT_EQ(correlator_kernel_named(correlator_kernel_name(GetParam())), GetParam());
  use_correlator_kernel(before);
}

INSTANTIATE_TEST_SUITE_P(Correlator, EveryKernel,
                         testing::Values(CorrelatorKernel::portable, CorrelatorKernel::avx2, CorrelatorKernel::avx512,
                                         CorrelatorKernel::neon),
                         [](const testing::TestParamInfo<CorrelatorKernel>& info) {
                           return std::string(correlator_kernel_name(info.param));
                         });

TEST(Correlator, TheFastestKernelIsTheNativeSimdOne) {
#if defined(__aarch64__)
  EXPECT_EQ(fastest_correlator_kernel(), CorrelatorKernel::neon);
#else
  EXPECT_EQ(fastest_correlator_kernel(), available_correlator_kernels().back());
#endif
  EXPECT_THROW(correlator_kernel_named("sse9"), std::invalid_argument);
}

TEST(Correlator, SpansOutsideTheSimdWindowsGiveTheSameIntegers) {
  // Code steps up to 2 chips per sample and taps several chips out do not fit the SIMD
  // kernels' chip windows (or only some of them): every kernel must still agree exactly.
  std::mt19937_64 rng(5);
  const double steps[] = {1.023e6 / 1.1e6, 1.023e6 / 0.9e6, 1.5, 2.0, 0.25};
  const double very[] = {0.0, 1.0, 3.0, 0.0, 9.0};
  for (int j = 0; j < 5; ++j) {
    RandomCase c = random_case(rng, 3001);
    c.span.code_step_chips = steps[j];
    c.span.very_spacing_chips = very[j];
    const auto& code = ca_code_chips(c.prn);
    const auto& noise = ca_code_chips(c.prn % 32 + 1);
    const CorrelatorSums p = correlate(CorrelatorKernel::portable, c.x.data(), 3001, c.span, code, noise);
    const CorrelatorSums ref = correlate_reference(c.x.data(), 3001, c.span, code, noise);
    double l1 = 0.0;
    for (const Sample& v : c.x) l1 += std::abs(std::complex<double>(v.real(), v.imag()));
    // Loose here (the bound of the reference test is below); it catches a wrong chip.
    EXPECT_LT(std::abs(p.prompt - ref.prompt), 0.12 * l1) << "step " << steps[j];
    EXPECT_LT(std::abs(p.very_early - ref.very_early), 0.12 * l1) << "step " << steps[j];
    for (CorrelatorKernel k : available_correlator_kernels()) {
      SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(k) << " step " << steps[j]);
      const CorrelatorSums s = correlate(k, c.x.data(), 3001, c.span, code, noise);
      EXPECT_EQ(s.early, p.early);
      EXPECT_EQ(s.prompt, p.prompt);
      EXPECT_EQ(s.late, p.late);
      EXPECT_EQ(s.very_early, p.very_early);
      EXPECT_EQ(s.very_late, p.very_late);
      EXPECT_EQ(s.noise, p.noise);
    }
  }
}

TEST(Correlator, EveryKernelMatchesTheSampleBySampleReference) {
  // Stated tolerance: the carrier replica is off by at most pi/32 in phase (|e^{j eps} - 1|
  // <= 0.099) and 0.5 % in amplitude, and a tap offset by at most 2.4e-4 chip moves at most
  // a few samples to a neighbouring chip. Worst case (every sample with the same phase
  // error, as at IF = fs/4) that is 0.105 |sum|; the per-sample part, random across
  // samples, adds about 0.06 sqrt(sum |x|^2) rms (6 sigma allowed) plus a few samples.
  std::mt19937_64 rng(77);
  for (int trial = 0; trial < 120; ++trial) {
    const int n = kLengths[trial % 6] + (trial % 12 >= 6 ? static_cast<int>(rng() % 64) : 0);
    const RandomCase c = random_case(rng, n);
    const auto& code = ca_code_chips(c.prn);
    const auto& noise = ca_code_chips(c.prn % 32 + 1);
    double power = 0.0, peak = 0.0;
    for (const Sample& v : c.x) {
      power += std::norm(std::complex<double>(v.real(), v.imag()));
      peak = std::max(peak, std::abs(std::complex<double>(v.real(), v.imag())));
    }
    const CorrelatorSums ref = correlate_reference(c.x.data(), n, c.span, code, noise);
    const auto tol = [&](std::complex<double> r) { return 0.105 * std::abs(r) + 0.36 * std::sqrt(power) + 4.0 * peak; };
    for (CorrelatorKernel k : available_correlator_kernels()) {
      SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(k) << " trial " << trial << " n " << n);
      const CorrelatorSums s = correlate(k, c.x.data(), n, c.span, code, noise);
      EXPECT_LE(std::abs(s.early - ref.early), tol(ref.early));
      EXPECT_LE(std::abs(s.prompt - ref.prompt), tol(ref.prompt));
      EXPECT_LE(std::abs(s.late - ref.late), tol(ref.late));
      EXPECT_LE(std::abs(s.very_early - ref.very_early), tol(ref.very_early));
      EXPECT_LE(std::abs(s.very_late - ref.very_late), tol(ref.very_late));
      EXPECT_LE(std::abs(s.noise - ref.noise), tol(ref.noise));
    }
  }
}

TEST(Correlator, AGivenMagnitudeBoundGivesTheScannedResultOrOneWithinTolerance) {
  // A block's magnitude bits, measured once, serve every channel's spans within it: the
  // span's own value must give the very integers of a scan, a larger bound (a louder part of
  // the block elsewhere) the reference within the same tolerance as above.
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = kLengths[trial % 6];
    const RandomCase c = random_case(rng, n);
    const auto& code = ca_code_chips(c.prn);
    const auto& noise = ca_code_chips(c.prn % 32 + 1);
    const int bits = sample_magnitude_bits(c.x.data(), n);
    double power = 0.0, peak = 0.0;
    for (const Sample& v : c.x) {
      power += std::norm(std::complex<double>(v.real(), v.imag()));
      peak = std::max(peak, std::abs(std::complex<double>(v.real(), v.imag())));
    }
    const CorrelatorSums ref = correlate_reference(c.x.data(), n, c.span, code, noise);
    for (CorrelatorKernel k : available_correlator_kernels()) {
      SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(k) << " trial " << trial << " bits " << bits);
      const CorrelatorSums scanned = correlate(k, c.x.data(), n, c.span, code, noise);
      CorrelatorSpan given = c.span;
      given.magnitude_bits = bits;
      const CorrelatorSums same = correlate(k, c.x.data(), n, given, code, noise);
      EXPECT_EQ(same.prompt, scanned.prompt);
      EXPECT_EQ(same.early, scanned.early);
      EXPECT_EQ(same.noise, scanned.noise);
      given.magnitude_bits = std::min(16, bits + 1 + trial % 3);
      const CorrelatorSums bound = correlate(k, c.x.data(), n, given, code, noise);
      const auto tol = [&](std::complex<double> r) {
        return 0.105 * std::abs(r) + 0.36 * std::sqrt(power) + 4.0 * peak;
      };
      EXPECT_LE(std::abs(bound.prompt - ref.prompt), tol(ref.prompt));
      EXPECT_LE(std::abs(bound.late - ref.late), tol(ref.late));
    }
  }
  CorrelatorSpan bad;
  bad.code_step_chips = 0.25;
  bad.magnitude_bits = 17;
  const std::vector<Sample> x(64);
  EXPECT_THROW(correlate(x.data(), 64, bad, ca_code_chips(1), ca_code_chips(2)), std::invalid_argument);
  EXPECT_EQ(sample_magnitude_bits(x.data(), 64), 0);
}

TEST(Correlator, PlanarCopiesOfTheSamplesGiveTheSameIntegers) {
  // The receiver deinterleaves each block once for all its channels; with or without that
  // copy (and at any offset into it, as the channels' spans fall) every kernel gives the
  // same sums.
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = kLengths[trial % 6] + static_cast<int>(rng() % 40);
    const RandomCase c = random_case(rng, n);
    SampleBlock block;
    block.samples = c.x;
    prepare_for_correlation(block);
    EXPECT_EQ(block.magnitude_bits, sample_magnitude_bits(c.x.data(), n));
    std::vector<std::int16_t> i(c.x.size()), q(c.x.size());
    deinterleave(c.x.data(), n, i.data(), q.data());
    for (int k = 0; k < n; ++k) ASSERT_EQ(i[static_cast<std::size_t>(k)], c.x[static_cast<std::size_t>(k)].real());
    for (int k = 0; k < n; ++k) ASSERT_EQ(q[static_cast<std::size_t>(k)], c.x[static_cast<std::size_t>(k)].imag());
    const int offset = static_cast<int>(rng() % 17);
    const CorrelatorInput planar{c.x.data() + offset, i.data() + offset, q.data() + offset};
    const auto& code = ca_code_chips(c.prn);
    const auto& noise = ca_code_chips(c.prn % 32 + 1);
    for (CorrelatorKernel k : available_correlator_kernels()) {
      SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(k) << " trial " << trial);
      const CorrelatorSums a = correlate(k, c.x.data() + offset, n - offset, c.span, code, noise);
      const CorrelatorSums b = correlate(k, planar, n - offset, c.span, code, noise);
      EXPECT_EQ(a.early, b.early);
      EXPECT_EQ(a.prompt, b.prompt);
      EXPECT_EQ(a.late, b.late);
      EXPECT_EQ(a.very_early, b.very_early);
      EXPECT_EQ(a.very_late, b.very_late);
      EXPECT_EQ(a.noise, b.noise);
    }
  }
}

TEST(Correlator, CarrierPhaseAndAmplitudeErrorsAreWithinTheTableResolution) {
  // A noise-free signal on the prompt: the prompt's phase is the replica's phase error,
  // which must stay within the 32-level table's +-5.625 degrees plus the 21-bit phase
  // step's drift over a run (0.35 degree), and its magnitude within the table's amplitude
  // rounding and the 0.16 % mean loss of the phase steps.
  const int n = 4092;
  const double step = 1.023e6 / 4.092e6;
  for (double amplitude : {3.0, 100.0, 20000.0}) {
    for (double phase0 = 0.0; phase0 < 1.0; phase0 += 0.0371) {
      for (double doppler : {0.0, 1023.0, -4321.0}) {
        CorrelatorSpan span;
        span.code_step_chips = step;
        span.code_phase_chips = 10.0;
        span.carrier_phase_cycles = phase0;
        span.carrier_step_cycles = doppler / 4.092e6;
        std::vector<Sample> x(n);
        const auto& code = ca_code_chips(5);
        for (int k = 0; k < n; ++k) {
          const double lvl = code[static_cast<std::size_t>(std::floor(10.0 + k * step)) % 1023];
          const double ph = 2.0 * M_PI * (phase0 + k * span.carrier_step_cycles);
          x[static_cast<std::size_t>(k)] = {static_cast<std::int16_t>(std::lround(amplitude * lvl * std::cos(ph))),
                                            static_cast<std::int16_t>(std::lround(amplitude * lvl * std::sin(ph)))};
        }
        const CorrelatorSums ref = correlate_reference(x.data(), n, span, code, ca_code_chips(6));
        for (CorrelatorKernel k : available_correlator_kernels()) {
          const CorrelatorSums s = correlate(k, x.data(), n, span, code, ca_code_chips(6));
          const double err_deg = std::abs(std::arg(s.prompt / ref.prompt)) * 180.0 / M_PI;
          EXPECT_LT(err_deg, 5.625 + 0.35)
              << "amplitude " << amplitude << " phase " << phase0 << " doppler " << doppler;
          EXPECT_NEAR(std::abs(s.prompt) / std::abs(ref.prompt), 1.0, 0.01) << "amplitude " << amplitude;
        }
      }
    }
  }
}

TEST(Correlator, ACodeChangedAtTheSameAddressIsNotServedFromACache) {
  const auto x = make_signal(9, 4092, 100.0, 0.25, 0.0, 40.0f, 3);
  CorrelatorSpan span;
  span.code_phase_chips = 100.0;
  span.code_step_chips = 0.25;
  CaCodeChips code = ca_code_chips(3);
  CaCodeChips noise = ca_code_chips(4);
  for (CorrelatorKernel k : available_correlator_kernels()) {
    (void)correlate(k, x.data(), 4092, span, code, noise);
    code = ca_code_chips(9);
    const CorrelatorSums changed = correlate(k, x.data(), 4092, span, code, noise);
    const CorrelatorSums fresh = correlate(k, x.data(), 4092, span, ca_code_chips(9), ca_code_chips(4));
    EXPECT_EQ(changed.prompt, fresh.prompt) << static_cast<int>(k);
    EXPECT_GT(std::abs(changed.prompt), 0.9 * 40.0 * 4092);
    code = ca_code_chips(3);
  }
}

TEST(Correlator, VeryEarlyLateAreZeroWhenDisabled) {
  const auto x = make_signal(3, 2000, 5.0, 0.25, 0.0, 50.0f, 2);
  CorrelatorSpan span;
  span.code_phase_chips = 5.0;
  span.code_step_chips = 0.25;
  const CorrelatorSums s = correlate(x.data(), 2000, span, ca_code_chips(3), ca_code_chips(4));
  EXPECT_EQ(s.very_early, std::complex<double>(0.0));
  EXPECT_EQ(s.very_late, std::complex<double>(0.0));
  EXPECT_GT(std::abs(s.prompt), 0.9 * 50.0 * 2000);
}

TEST(Correlator, RejectsAnImpossibleCodeStep) {
  const std::vector<Sample> x(10);
  CorrelatorSpan span;
  span.code_step_chips = 0.0;
  EXPECT_THROW(correlate(x.data(), 10, span, ca_code_chips(1), ca_code_chips(2)), std::invalid_argument);
}

TEST(Correlator, TriangleResponseAndZeroEarlyMinusLateAtAlignment) {
  // Noise-free signal at 4 Msps, not commensurate with the chip rate, so the samples fall
  // on all chip fractions: the correlation is the ideal triangle 1 - |offset| sampled.
  const double fs = 4.0e6, step = 1.023e6 / fs;
  const int n = 16000;
  const float a = 100.0f;
  std::vector<float> i(n), q(n), scratch(n);
  SignalSegment sg;
  sg.code_phase_chips = 200.0;
  sg.code_step_chips = step;
  sg.carrier_step_cycles = 1000.0 / fs;
  sg.amplitude = a;
  add_satellite_segment(i.data(), q.data(), n, sg, ca_code_chips(12), scratch.data());
  std::vector<Sample> x(n);
  for (int k = 0; k < n; ++k)
    x[k] = {static_cast<std::int16_t>(std::lround(i[k])), static_cast<std::int16_t>(std::lround(q[k]))};

  CorrelatorSpan span;
  span.code_step_chips = step;
  span.carrier_step_cycles = 1000.0 / fs;
  span.spacing_chips = 0.5;
  const double full = a * n;
  for (CorrelatorKernel kernel : available_correlator_kernels()) {
    SCOPED_TRACE(static_cast<int>(kernel));
    for (double offset = -1.5; offset <= 1.5; offset += 0.125) {
      span.code_phase_chips = 200.0 + offset;
      const CorrelatorSums s = correlate(kernel, x.data(), n, span, ca_code_chips(12), ca_code_chips(13));
      const double expected = std::max(0.0, 1.0 - std::abs(offset));
      // Off the peak the C/A cross-correlation sidelobes stay within about 1/1023 * 65.
      EXPECT_NEAR(std::abs(s.prompt) / full, expected, 0.02) << "offset " << offset;
      EXPECT_LT(std::abs(s.noise) / full, 0.08);
      if (std::abs(offset) <= 0.25) {
        // Normalised E-L: the replica late (offset < 0) makes the early tap stronger.
        const double e = std::abs(s.early) / full, l = std::abs(s.late) / full;
        EXPECT_NEAR(e - l, -2.0 * offset, 0.03) << "offset " << offset;
      }
    }
    span.code_phase_chips = 200.0;
    const CorrelatorSums s = correlate(kernel, x.data(), n, span, ca_code_chips(12), ca_code_chips(13));
    EXPECT_NEAR((std::abs(s.early) - std::abs(s.late)) / full, 0.0, 0.005);
    EXPECT_NEAR(std::abs(s.early) / full, 0.75, 0.02);
  }
}

}  // namespace
}  // namespace deepnav
