#include "signals/sim/tone_generator.hpp"

#include <algorithm>
#include <cmath>

#include "signals/sim/floor_div.hpp"

namespace deepnav {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kTwoPowMinus64 = 1.0 / 18446744073709551616.0;

/// Fraction of a cycle per sample as a 64-bit fixed-point number (negative frequencies wrap).
std::uint64_t fixed_point_step(double frequency_hz, double sample_rate_hz) {
  double cycles = frequency_hz / sample_rate_hz;
  cycles -= std::floor(cycles);
  const double scaled = std::ldexp(cycles, 64);
  return scaled >= 18446744073709551616.0 ? 0 : static_cast<std::uint64_t>(scaled);
}

std::complex<double> unit_phasor(double cycles) { return {std::cos(kTwoPi * cycles), std::sin(kTwoPi * cycles)}; }

}  // namespace

ToneGenerator::ToneGenerator(double frequency_hz, double sample_rate_hz)
    : step_(fixed_point_step(frequency_hz, sample_rate_hz)), table_re_(kTable), table_im_(kTable) {
  for (int m = 0; m < kTable; ++m) {
    const std::complex<double> z =
        unit_phasor(static_cast<double>(step_ * static_cast<std::uint64_t>(m)) * kTwoPowMinus64);
    table_re_[m] = static_cast<float>(z.real());
    table_im_[m] = static_cast<float>(z.imag());
  }
}

std::complex<double> ToneGenerator::anchor(std::int64_t sample) const {
  const std::uint64_t phase = static_cast<std::uint64_t>(sample) * step_;  // exact modulo 2^64
  return unit_phasor(static_cast<double>(phase) * kTwoPowMinus64);
}

// Anchors sit at absolute multiples of kTable, so every sample is computed the same way
// whatever the block boundaries are (bit-identical output for any block partition).
void ToneGenerator::generate(std::span<std::complex<float>> out, std::int64_t first_sample, float amplitude) const {
  float* io = reinterpret_cast<float*>(out.data());
  const std::int64_t n = static_cast<std::int64_t>(out.size());
  for (std::int64_t k = 0; k < n;) {
    const std::int64_t sample = first_sample + k;
    const std::int64_t base = floor_div(sample, kTable) * kTable;
    const int m0 = static_cast<int>(sample - base);
    const int count = static_cast<int>(std::min<std::int64_t>(kTable - m0, n - k));
    const std::complex<double> a = anchor(base) * static_cast<double>(amplitude);
    const float ar = static_cast<float>(a.real()), ai = static_cast<float>(a.imag());
    float* o = io + 2 * k;
    const float* tr = table_re_.data() + m0;
    const float* ti = table_im_.data() + m0;
    for (int j = 0; j < count; ++j) {
      o[2 * j] = ar * tr[j] - ai * ti[j];
      o[2 * j + 1] = ar * ti[j] + ai * tr[j];
    }
    k += count;
  }
}

void ToneGenerator::mix(std::span<std::complex<float>> out, std::int64_t first_sample) const {
  float* io = reinterpret_cast<float*>(out.data());
  const std::int64_t n = static_cast<std::int64_t>(out.size());
  for (std::int64_t k = 0; k < n;) {
    const std::int64_t sample = first_sample + k;
    const std::int64_t base = floor_div(sample, kTable) * kTable;
    const int m0 = static_cast<int>(sample - base);
    const int count = static_cast<int>(std::min<std::int64_t>(kTable - m0, n - k));
    const std::complex<double> a = anchor(base);
    const float ar = static_cast<float>(a.real()), ai = static_cast<float>(a.imag());
    float* o = io + 2 * k;
    for (int j = 0; j < count; ++j) {
      const float wr = ar * table_re_[m0 + j] - ai * table_im_[m0 + j];
      const float wi = ar * table_im_[m0 + j] + ai * table_re_[m0 + j];
      const float xr = o[2 * j], xi = o[2 * j + 1];
      o[2 * j] = xr * wr - xi * wi;
      o[2 * j + 1] = xr * wi + xi * wr;
    }
    k += count;
  }
}

ChirpGenerator::ChirpGenerator(double center_hz, double bandwidth_hz, double period_s, double sample_rate_hz)
    : f_low_hz_(center_hz - 0.5 * bandwidth_hz), bandwidth_hz_(bandwidth_hz), period_s_(period_s), fs_(sample_rate_hz) {
  const double per_sweep = center_hz * period_s;
  sweep_phase_frac_ = per_sweep - std::floor(per_sweep);
}

std::int64_t ChirpGenerator::sweep_start_sample(std::int64_t sweep) const {
  return static_cast<std::int64_t>(std::ceil(static_cast<double>(sweep) * period_s_ * fs_));
}

// The boundaries are defined by sweep_start_sample alone, so rounding in n / (T fs)
// can never put a sample in a sweep that does not contain it.
std::int64_t ChirpGenerator::sweep_of(std::int64_t sample) const {
  auto k = static_cast<std::int64_t>(std::floor(static_cast<double>(sample) / (period_s_ * fs_)));
  while (sweep_start_sample(k) > sample) --k;
  while (sweep_start_sample(k + 1) <= sample) ++k;
  return k;
}

double ChirpGenerator::phase_cycles(std::int64_t sweep, double tau_s) const {
  double whole = static_cast<double>(sweep) * sweep_phase_frac_;
  whole -= std::floor(whole);
  double p = whole + f_low_hz_ * tau_s + 0.5 * bandwidth_hz_ / period_s_ * tau_s * tau_s;
  return p - std::floor(p);
}

double ChirpGenerator::frequency_hz(std::int64_t sample) const {
  const std::int64_t k = sweep_of(sample);
  const double tau = (static_cast<double>(sample) - static_cast<double>(k) * period_s_ * fs_) / fs_;
  return f_low_hz_ + bandwidth_hz_ * tau / period_s_;
}

// Segments end at sweep restarts and at absolute multiples of kSegment, so the output does
// not depend on block boundaries. Within a segment the phase is quadratic in the sample
// offset j: z_{j+1} = z_j w_j, w_{j+1} = w_j dw, run in double from an exact anchor.
void ChirpGenerator::generate(std::span<std::complex<float>> out, std::int64_t first_sample, float amplitude) const {
  constexpr std::int64_t kSegment = 256;
  const double a = bandwidth_hz_ / (period_s_ * fs_ * fs_);  // chirp rate in cycles/sample^2
  const std::complex<double> dw = unit_phasor(a);
  const std::int64_t n = static_cast<std::int64_t>(out.size());
  for (std::int64_t k = 0; k < n;) {
    const std::int64_t sample = first_sample + k;
    const std::int64_t sweep = sweep_of(sample);
    const std::int64_t end =
        std::min({sweep_start_sample(sweep + 1), (floor_div(sample, kSegment) + 1) * kSegment, first_sample + n});
    // The recurrence always starts at the segment's own start, even when the block begins
    // inside the segment, so every sample is computed the same way.
    const std::int64_t anchor = std::max(sweep_start_sample(sweep), floor_div(sample, kSegment) * kSegment);
    const double tau = (static_cast<double>(anchor) - static_cast<double>(sweep) * period_s_ * fs_) / fs_;
    std::complex<double> z = unit_phasor(phase_cycles(sweep, tau)) * static_cast<double>(amplitude);
    std::complex<double> w = unit_phasor((f_low_hz_ + bandwidth_hz_ * tau / period_s_) / fs_ + 0.5 * a);
    for (std::int64_t s = anchor; s < end; ++s) {
      if (s >= sample)
        out[static_cast<std::size_t>(k++)] = {static_cast<float>(z.real()), static_cast<float>(z.imag())};
      const double zr = z.real() * w.real() - z.imag() * w.imag();
      const double zi = z.real() * w.imag() + z.imag() * w.real();
      z = {zr, zi};
      const double wr = w.real() * dw.real() - w.imag() * dw.imag();
      const double wi = w.real() * dw.imag() + w.imag() * dw.real();
      w = {wr, wi};
    }
  }
}

}  // namespace deepnav
