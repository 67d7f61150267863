// The Galileo E1 correlator: the double-precision reference against the signal layer's own
// BOC(1,1) replica, the fixed-point path against the reference, and every SIMD kernel
// bit-exact with the portable one.
#include "receiver/tracking/e1_correlator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "converter_samples.hpp"
#include "e1_test_signal.hpp"
#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/e1_modulation.hpp"

namespace deepnav {
namespace {

using testing::E1Signal;
using testing::E1SignalSpec;

struct Fixture {
  SampleBlock block;
  E1CorrelatorSpan span;
  E1CorrelatorCodes codes{&galileo::e1c_code_chips(11), &galileo::e1b_code_chips(11), &galileo::e1c_code_chips(12)};
  int n = 0;
};

/// 3 ms of a 60 dB-Hz PRN 11 signal whose span crosses the code's wrap.
Fixture strong_signal() {
  E1SignalSpec spec;
  spec.cn0_dbhz = 60.0;
  spec.code0_chips = 4000.2;
  E1Signal signal(spec);
  Fixture f;
  f.block = signal.next(3);
  f.n = static_cast<int>(f.block.samples.size());
  f.span.carrier_phase_cycles = 0.37;
  f.span.carrier_step_cycles = 1510.0 / spec.fs_hz;
  // Phases that never fall exactly on a chip or half-chip edge (where either level is right).
  f.span.code_phase_chips = 4000.31234567;
  f.span.code_step_chips = 1.023e6 * (1.0 + 1510.0 / galileo::kE1_Hz) / spec.fs_hz;
  return f;
}

TEST(E1Correlator, ReferenceMatchesASampleBySampleSumOverTheSignalLayersReplica) {
  const Fixture f = strong_signal();
  const E1CorrelatorSums ref = correlate_e1_reference(f.block.samples.data(), f.n, f.span, f.codes);
  const auto replica_sum = [&](const galileo::E1CodeChips& code, double offset) {
    const std::vector<float> replica =
        galileo::e1_replica(code, galileo::E1Subcarrier::kBoc11, f.span.code_phase_chips + offset,
                            f.span.code_step_chips, static_cast<std::size_t>(f.n));
    std::complex<double> sum;
    for (int k = 0; k < f.n; ++k) {
      const double phase = f.span.carrier_phase_cycles + k * f.span.carrier_step_cycles;
      const auto& x = f.block.samples[static_cast<std::size_t>(k)];
      sum += std::complex<double>(x.real(), x.imag()) * std::polar(1.0, -2.0 * M_PI * phase) *
             static_cast<double>(replica[static_cast<std::size_t>(k)]);
    }
    return sum;
  };
  const auto expect_close = [&](const std::complex<double>& a, const std::complex<double>& b) {
    EXPECT_LT(std::abs(a - b), 1e-6 * f.n * 64.0) << a << " vs " << b;
  };
  expect_close(ref.prompt, replica_sum(*f.codes.pilot, 0.0));
  expect_close(ref.early, replica_sum(*f.codes.pilot, 0.1));
  expect_close(ref.late, replica_sum(*f.codes.pilot, -0.1));
  expect_close(ref.very_early, replica_sum(*f.codes.pilot, 0.5));
  expect_close(ref.very_late, replica_sum(*f.codes.pilot, -0.5));
  expect_close(ref.data_prompt, replica_sum(*f.codes.data, 0.0));
  expect_close(ref.noise, replica_sum(*f.codes.noise, 0.0));
  // At 60 dB-Hz the aligned pilot stands far above the noise reference.
  EXPECT_GT(std::abs(ref.prompt), 10.0 * std::abs(ref.noise));
}

TEST(E1Correlator, FixedPointSumsAreWithinTheCarrierTablesErrorOfTheReference) {
  const Fixture f = strong_signal();
  const E1CorrelatorSums ref = correlate_e1_reference(f.block.samples.data(), f.n, f.span, f.codes);
  for (CorrelatorKernel k : available_correlator_kernels()) {
    SCOPED_TRACE(correlator_kernel_name(k));
    const E1CorrelatorSums fast = correlate_e1(k, CorrelatorInput{f.block.samples.data()}, f.n, f.span, f.codes);
    // The 32-bin carrier table: a 0.16 % mean amplitude loss and +-5.6 degrees per sample that
    // average out; 1 % of the aligned pilot bounds every tap's difference.
    const double bound = 0.01 * std::abs(ref.prompt);
    EXPECT_LT(std::abs(fast.prompt - ref.prompt), bound);
    EXPECT_LT(std::abs(fast.early - ref.early), bound);
    EXPECT_LT(std::abs(fast.late - ref.late), bound);
    EXPECT_LT(std::abs(fast.very_early - ref.very_early), bound);
    EXPECT_LT(std::abs(fast.very_late - ref.very_late), bound);
    EXPECT_LT(std::abs(fast.data_prompt - ref.data_prompt), bound);
    EXPECT_LT(std::abs(fast.noise - ref.noise), bound);
  }
}

/// A random span and input: sample rates 2.046-20 Msps (commensurate with the 2.046 MHz
/// half-chip rate or not), spacings 0.05-0.6 chip, VE/VL on or off, Doppler +-10 kHz on an IF
/// up to fs/4, inputs from 1 bit to full-scale int16 (converter_samples.hpp), a BOC(1,1)
/// pilot near the prompt.
struct RandomCase {
  E1CorrelatorSpan span;
  std::vector<Sample> x;
  E1CorrelatorCodes codes;
};

RandomCase random_case(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  static const double kRates[] = {2.046e6, 4.0e6, 4.092e6, 5.0e6, 8.184e6, 12.0e6, 20.0e6};
  const double fs = u(rng) < 0.5 ? kRates[rng() % 7] : 2.046e6 + u(rng) * (20.0e6 - 2.046e6);
  RandomCase c;
  const int prn = 1 + static_cast<int>(rng() % galileo::kMaxPrn);
  c.codes = {&galileo::e1c_code_chips(prn), &galileo::e1b_code_chips(prn),
             &galileo::e1c_code_chips(prn % galileo::kMaxPrn + 1)};
  E1CorrelatorSpan& s = c.span;
  s.code_step_chips = std::min(1.0, 1.023e6 / fs * (1.0 + (u(rng) - 0.5) * 6e-6));
  const double if_hz = u(rng) < 0.3 ? 0.0 : u(rng) * fs / 4.0;
  s.carrier_step_cycles = (if_hz + (u(rng) - 0.5) * 20e3) / fs;
  s.carrier_phase_cycles = (u(rng) - 0.5) * 10.0;
  s.code_phase_chips = (u(rng) - 0.5) * 20000.0;
  s.spacing_chips = 0.05 + 0.55 * u(rng);
  s.very_spacing_chips = u(rng) < 0.3 ? 0.0 : s.spacing_chips + u(rng) * (1.2 - s.spacing_chips);
  s.noise_tap = u(rng) < 0.7;

  const auto kind = static_cast<test_input::Converter>(rng() % test_input::kConverters);
  const double amp = test_input::converter_amplitude(kind);
  const double lag = (u(rng) - 0.5) * 0.3;
  c.x.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double lvl = boc11_level(*c.codes.pilot, s.code_phase_chips + lag + k * s.code_step_chips);
    const double ph = 2.0 * M_PI * (s.carrier_phase_cycles + 0.1 + k * s.carrier_step_cycles);
    c.x[static_cast<std::size_t>(k)] =
        test_input::converter_sample(kind, amp * lvl * std::cos(ph), amp * lvl * std::sin(ph), rng);
  }
  return c;
}

TEST(E1Correlator, EveryKernelIsBitExactWithThePortableOneWithAndWithoutPlanarInput) {
  std::mt19937_64 rng(20261205);
  constexpr int kLengths[] = {1, 31, 4092, 8000, 16368};
  for (int trial = 0; trial < 120; ++trial) {
    const int n = kLengths[trial % 5] + static_cast<int>(rng() % 64);
    const RandomCase c = random_case(rng, n);
    std::vector<std::int16_t> i(c.x.size()), q(c.x.size());
    for (std::size_t k = 0; k < c.x.size(); ++k) {
      i[k] = c.x[k].real();
      q[k] = c.x[k].imag();
    }
    const E1CorrelatorSums p =
        correlate_e1(CorrelatorKernel::portable, CorrelatorInput{c.x.data()}, n, c.span, c.codes);
    if (!c.span.noise_tap) {
      EXPECT_EQ(p.noise, std::complex<double>());
    }
    for (CorrelatorKernel k : available_correlator_kernels()) {
      for (const CorrelatorInput& input :
           {CorrelatorInput{c.x.data()}, CorrelatorInput{c.x.data(), i.data(), q.data()}}) {
        SCOPED_TRACE(::testing::Message()
                     << correlator_kernel_name(k) << " trial " << trial << " n " << n << (input.i ? " planar" : ""));
        const E1CorrelatorSums s = correlate_e1(k, input, n, c.span, c.codes);
        EXPECT_EQ(s.very_early, p.very_early);
        EXPECT_EQ(s.early, p.early);
        EXPECT_EQ(s.prompt, p.prompt);
        EXPECT_EQ(s.late, p.late);
        EXPECT_EQ(s.very_late, p.very_late);
        EXPECT_EQ(s.data_prompt, p.data_prompt);
        EXPECT_EQ(s.noise, p.noise);
      }
    }
  }
}

TEST(E1Correlator, TheNoisePassChangesNoOtherSum) {
  const Fixture f = strong_signal();
  E1CorrelatorSpan without = f.span;
  without.noise_tap = false;
  const E1CorrelatorSums a = correlate_e1(CorrelatorInput{f.block.samples.data()}, f.n, f.span, f.codes);
  const E1CorrelatorSums b = correlate_e1(CorrelatorInput{f.block.samples.data()}, f.n, without, f.codes);
  EXPECT_EQ(a.prompt, b.prompt);
  EXPECT_EQ(a.very_late, b.very_late);
  EXPECT_EQ(a.data_prompt, b.data_prompt);
  EXPECT_NE(a.noise, std::complex<double>());
  EXPECT_EQ(b.noise, std::complex<double>());
}

TEST(E1Correlator, RefusesACodeStepAboveOneChipOrAMissingCode) {
  Fixture f = strong_signal();
  const CorrelatorInput input{f.block.samples.data()};
  f.span.code_step_chips = 1.5;
  EXPECT_THROW(correlate_e1(input, f.n, f.span, f.codes), std::invalid_argument);
  EXPECT_THROW(correlate_e1_reference(f.block.samples.data(), f.n, f.span, f.codes), std::invalid_argument);
  f.span.code_step_chips = 0.25;
  f.codes.noise = nullptr;
  EXPECT_THROW(correlate_e1(input, f.n, f.span, f.codes), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
