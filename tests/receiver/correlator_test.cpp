#include "receiver/correlator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "signals/satellite_signal_kernel.hpp"

namespace deepnav {
namespace {

/// n samples of PRN `prn` at code phase `code0` with amplitude `a` plus uniform int noise.
std::vector<Sample> make_signal(int prn, int n, double code0, double code_step, double carrier_step, float a,
                                std::uint64_t seed) {
  std::vector<float> i(static_cast<std::size_t>(n)), q(static_cast<std::size_t>(n)), scratch(static_cast<std::size_t>(n));
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
    out[k] = {static_cast<std::int16_t>(std::lround(i[k]) + noise(rng)), static_cast<std::int16_t>(std::lround(q[k]) + noise(rng))};
  return out;
}

void expect_close(const std::complex<double>& fast, const std::complex<double>& ref, double scale, const char* what) {
  // Float arithmetic over a run against a double reference: relative 1e-4 of the sum's scale.
  EXPECT_LT(std::abs(fast - ref), 1e-4 * scale) << what << " fast " << fast << " reference " << ref;
}

TEST(Correlator, EveryKernelMatchesTheSampleBySampleReference) {
  struct Case {
    double code_step, carrier_step, code0;
    int n;
  };
  // Steps of 4.092, 2.046 and 1.1 Msps (the last takes the gather path of the AVX kernels);
  // spans of several runs, odd lengths, code phases about to wrap and negative ones.
  const Case cases[] = {{1.023e6 / 4.092e6 * 1.0000013, 1234.5 / 4.092e6, 1022.9, 4092},
                        {1.023e6 / 2.046e6 * 0.9999991, -3210.0 / 2.046e6, 17.25, 5003},
                        {1.023e6 / 1.1e6 * 1.0000007, 777.0 / 1.1e6, -3.31, 1100},
                        {1.023e6 / 4.092e6, 0.0, 0.0, 13}};
  for (const Case& c : cases) {
    const auto x = make_signal(7, c.n, std::fmod(c.code0 + 1023.0, 1023.0) + 0.1, c.code_step, c.carrier_step, 30.0f, 11);
    CorrelatorSpan span;
    span.code_phase_chips = c.code0;
    span.code_step_chips = c.code_step;
    span.carrier_phase_cycles = 0.25;
    span.carrier_step_cycles = c.carrier_step;
    span.spacing_chips = 0.5;
    span.very_spacing_chips = 1.2;
    const CorrelatorSums ref = correlate_reference(x.data(), c.n, span, ca_code_chips(7), ca_code_chips(8));
    const double scale = 30.0 * c.n + 40.0 * std::sqrt(c.n) * 10.0;
    for (CorrelatorKernel k : available_correlator_kernels()) {
      SCOPED_TRACE(static_cast<int>(k));
      SCOPED_TRACE(c.n);
      const CorrelatorSums s = correlate(k, x.data(), c.n, span, ca_code_chips(7), ca_code_chips(8));
      expect_close(s.early, ref.early, scale, "early");
      expect_close(s.prompt, ref.prompt, scale, "prompt");
      expect_close(s.late, ref.late, scale, "late");
      expect_close(s.very_early, ref.very_early, scale, "very early");
      expect_close(s.very_late, ref.very_late, scale, "very late");
      expect_close(s.noise, ref.noise, scale, "noise");
    }
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
  for (int k = 0; k < n; ++k) x[k] = {static_cast<std::int16_t>(std::lround(i[k])), static_cast<std::int16_t>(std::lround(q[k]))};

  CorrelatorSpan span;
  span.code_step_chips = step;
  span.carrier_step_cycles = 1000.0 / fs;
  span.spacing_chips = 0.5;
  const double full = a * n;
  for (double offset = -1.5; offset <= 1.5; offset += 0.125) {
    span.code_phase_chips = 200.0 + offset;
    const CorrelatorSums s = correlate(x.data(), n, span, ca_code_chips(12), ca_code_chips(13));
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
  const CorrelatorSums s = correlate(x.data(), n, span, ca_code_chips(12), ca_code_chips(13));
  EXPECT_NEAR((std::abs(s.early) - std::abs(s.late)) / full, 0.0, 0.005);
  EXPECT_NEAR(std::abs(s.early) / full, 0.75, 0.02);
}

}  // namespace
}  // namespace deepnav
