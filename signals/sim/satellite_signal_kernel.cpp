#include "signals/sim/satellite_signal_kernel.hpp"

#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>

namespace deepnav {
namespace {

constexpr int kLanes = 16;  // phasors advanced in parallel: a multiple of every SIMD width we target

// On x86-64 the two inner loops are compiled for AVX-512, AVX2 and the baseline; the loader
// picks the best one the CPU has (the code index becomes a vector gather on AVX2 and later).
// Elsewhere (AArch64: NEON is baseline) they are compiled once.
#if defined(__x86_64__)
#define DEEPNAV_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define DEEPNAV_SIMD_CLONES
#endif

/// out[k] = amplitude * code[(acc + k inc) >> 32] for n samples that do not wrap the code.
DEEPNAV_SIMD_CLONES
void fill_code_run(float* __restrict out, int n, std::uint64_t acc, std::uint64_t inc,
                   const float* __restrict code_levels) {
  for (int k = 0; k < n; ++k) out[k] = code_levels[(acc + static_cast<std::uint64_t>(k) * inc) >> 32];
}

/// i/q[k] += scratch[k] * phasor(k) with kLanes phasors rotated by w each kLanes samples.
DEEPNAV_SIMD_CLONES
void mix_carrier(float* __restrict i_out, float* __restrict q_out, int n, const float* __restrict scratch,
                 float* __restrict re, float* __restrict im, float wr, float wi) {
  int k = 0;
  for (; k + kLanes <= n; k += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      i_out[k + l] += scratch[k + l] * re[l];
      q_out[k + l] += scratch[k + l] * im[l];
      const float nr = re[l] * wr - im[l] * wi;
      const float ni = re[l] * wi + im[l] * wr;
      re[l] = nr;
      im[l] = ni;
    }
  }
  for (int l = 0; k < n; ++k, ++l) {
    i_out[k] += scratch[k] * re[l];
    q_out[k] += scratch[k] * im[l];
  }
}

/// Code chip levels times amplitude for n samples, from a 32.32 fixed-point chip
/// accumulator, in runs that stop at each code wrap.
void fill_code(float* out, int n, double chip0, double step, const CaCodeChips& code, float amplitude) {
  constexpr double kOne = 4294967296.0;  // 2^32
  constexpr std::uint64_t kPeriod = 1023ULL << 32;
  // The accumulator below advances by at least one unit and by less than a code period per
  // sample only for a step in [2^-32, 1023) chips: anything else (a NaN, zero or negative step,
  // or one beyond a whole code per sample) would never reach the period end.
  if (!(step * kOne >= 1.0 && step < 1023.0) || !(chip0 >= 0.0 && chip0 < 1023.0)) {
    // (No fmt here: this file is also cross-compiled on its own for the AArch64 tests.)
    char what[160];
    std::snprintf(what, sizeof what,
                  "signal kernel: code phase %g chips advancing %g chips per sample is outside [0, 1023) chips "
                  "and (0, 1023) chips per sample",
                  chip0, step);
    throw std::invalid_argument(what);
  }
  float levels[1023];
  for (int c = 0; c < 1023; ++c) levels[c] = amplitude * static_cast<float>(code[c]);
  std::uint64_t acc = static_cast<std::uint64_t>(chip0 * kOne);
  const std::uint64_t inc = static_cast<std::uint64_t>(step * kOne + 0.5);
  int k = 0;
  while (k < n) {
    if (acc >= kPeriod) acc -= kPeriod;
    // Samples left before the accumulator reaches the period end.
    const std::uint64_t left = (kPeriod - acc + inc - 1) / inc;
    const int run = static_cast<int>(std::min<std::uint64_t>(left, static_cast<std::uint64_t>(n - k)));
    fill_code_run(out + k, run, acc, inc, levels);
    acc += static_cast<std::uint64_t>(run) * inc;
    k += run;
  }
}

/// out[k] = amplitude * levels[(acc + k inc) >> 32] for n samples that do not wrap the table.
DEEPNAV_SIMD_CLONES
void fill_scaled_run(float* __restrict out, int n, std::uint64_t acc, std::uint64_t inc, const float* __restrict levels,
                     float amplitude) {
  for (int k = 0; k < n; ++k) out[k] = amplitude * levels[(acc + static_cast<std::uint64_t>(k) * inc) >> 32];
}

/// Mixes scratch onto the segment's carrier. Lane l starts at sample l and every lane steps
/// kLanes samples at a time. The lane phasors come from two exact exponentials by
/// double-precision products (error ~1e-15); float rotation over one millisecond (a few
/// hundred steps) stays below 1e-5 rad.
void mix_segment(float* i_out, float* q_out, int n, const SignalSegment& s, const float* scratch) {
  const double two_pi = 2.0 * M_PI;
  const double phase0 = s.carrier_phase_cycles - std::floor(s.carrier_phase_cycles);
  const std::complex<double> step = std::polar(1.0, two_pi * s.carrier_step_cycles);
  std::complex<double> z = std::polar(1.0, two_pi * phase0);
  alignas(64) float re[kLanes], im[kLanes];
  for (int l = 0; l < kLanes; ++l, z *= step) {
    re[l] = static_cast<float>(z.real());
    im[l] = static_cast<float>(z.imag());
  }
  const std::complex<double> w = std::polar(1.0, two_pi * kLanes * s.carrier_step_cycles);
  mix_carrier(i_out, q_out, n, scratch, re, im, static_cast<float>(w.real()), static_cast<float>(w.imag()));
}

}  // namespace

void add_e1_segment(float* __restrict i_out, float* __restrict q_out, int n, const SignalSegment& s,
                    const float* waveform, float* __restrict scratch) {
  if (n <= 0) return;
  constexpr double kOne = 4294967296.0;  // 2^32
  constexpr std::uint64_t kEntries = 4092ULL * kE1SubchipsPerChip;
  constexpr std::uint64_t kPeriod = kEntries << 32;
  const double first = s.code_phase_chips * kE1SubchipsPerChip;
  const double step = s.code_step_chips * kE1SubchipsPerChip;
  if (!(step * kOne >= 1.0 && step < static_cast<double>(kEntries)) ||
      !(first >= 0.0 && first < static_cast<double>(kEntries))) {
    char what[160];
    std::snprintf(what, sizeof what,
                  "signal kernel: E1 code phase %g chips advancing %g chips per sample is outside [0, 4092) chips "
                  "and (0, 4092) chips per sample",
                  s.code_phase_chips, s.code_step_chips);
    throw std::invalid_argument(what);
  }
  std::uint64_t acc = static_cast<std::uint64_t>(first * kOne);
  const std::uint64_t inc = static_cast<std::uint64_t>(step * kOne + 0.5);
  int k = 0;
  while (k < n) {
    if (acc >= kPeriod) acc -= kPeriod;
    const std::uint64_t left = (kPeriod - acc + inc - 1) / inc;
    const int run = static_cast<int>(std::min<std::uint64_t>(left, static_cast<std::uint64_t>(n - k)));
    fill_scaled_run(scratch + k, run, acc, inc, waveform, s.amplitude);
    acc += static_cast<std::uint64_t>(run) * inc;
    k += run;
  }
  mix_segment(i_out, q_out, n, s, scratch);
}

void add_satellite_segment(float* __restrict i_out, float* __restrict q_out, int n, const SignalSegment& s,
                           const CaCodeChips& code, float* __restrict scratch) {
  if (n <= 0) return;
  fill_code(scratch, n, s.code_phase_chips, s.code_step_chips, code, s.amplitude);
  mix_segment(i_out, q_out, n, s, scratch);
}

}  // namespace deepnav
