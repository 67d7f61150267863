#include "signals/satellite_signal_kernel.hpp"

#include <cmath>

namespace deepnav {
namespace {

constexpr int kLanes = 16;  // phasors advanced in parallel: a multiple of every SIMD width we target

/// Code chip levels times amplitude for n samples, from a 32.32 fixed-point chip accumulator.
void fill_code(float* out, int n, double chip0, double step, const CaCodeChips& code, float amplitude) {
  constexpr double kOne = 4294967296.0;  // 2^32
  constexpr std::uint64_t kPeriod = 1023ULL << 32;
  std::uint64_t acc = static_cast<std::uint64_t>(chip0 * kOne);
  const std::uint64_t inc = static_cast<std::uint64_t>(step * kOne + 0.5);
  float level[2];
  for (int k = 0; k < n; ++k) {
    if (acc >= kPeriod) acc -= kPeriod;
    level[0] = amplitude;
    level[1] = -amplitude;
    out[k] = level[code[acc >> 32] < 0];
    acc += inc;
  }
}

}  // namespace

void add_satellite_segment(float* __restrict i_out, float* __restrict q_out, int n, const SignalSegment& s,
                           const CaCodeChips& code, float* __restrict scratch) {
  if (n <= 0) return;
  fill_code(scratch, n, s.code_phase_chips, s.code_step_chips, code, s.amplitude);

  // Lane l starts at sample l and every lane steps kLanes samples at a time. The phasors
  // start from exact double-precision values; float rotation error over one millisecond
  // (a few hundred steps) stays below 1e-5 rad.
  alignas(64) float re[kLanes], im[kLanes];
  const double two_pi = 2.0 * M_PI;
  const double phase0 = s.carrier_phase_cycles - std::floor(s.carrier_phase_cycles);
  for (int l = 0; l < kLanes; ++l) {
    const double ph = two_pi * (phase0 + l * s.carrier_step_cycles);
    re[l] = static_cast<float>(std::cos(ph));
    im[l] = static_cast<float>(std::sin(ph));
  }
  const double step_angle = two_pi * kLanes * s.carrier_step_cycles;
  const float wr = static_cast<float>(std::cos(step_angle));
  const float wi = static_cast<float>(std::sin(step_angle));

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

}  // namespace deepnav
