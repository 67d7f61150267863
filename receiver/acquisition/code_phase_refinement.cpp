#include "receiver/acquisition/code_phase_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

using Baseband = std::vector<std::complex<float>>;

/// A step this small ends the search: the correlation moves in steps of about
/// 1 / (samples per code period) chip as the replica's chip edges pass the samples, and
/// below that the secant only chases those steps. 2e-3 chip is 0.6 m.
constexpr double kSettled_chips = 2e-3;

/// The samples times exp(-j 2 pi f n / fs): the phasor is advanced by multiplication in
/// double precision and renormalised each block so that its length does not drift.
Baseband wiped_off(std::span<const Sample> samples, double carrier_hz, double fs_hz) {
  Baseband out(samples.size());
  const double w = -2.0 * std::numbers::pi * carrier_hz / fs_hz;
  const std::complex<double> step(std::cos(w), std::sin(w));
  std::complex<double> phasor(1.0, 0.0);
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const std::complex<double> s(samples[n].real(), samples[n].imag());
    out[n] = std::complex<float>(s * phasor);
    phasor *= step;
    if ((n & 1023u) == 1023u) phasor /= std::abs(phasor);
  }
  return out;
}

/// What one correlation needs: the wiped-off samples, the code and its rate.
struct Correlation {
  const Baseband& x;
  const CaCodeChips& code;
  double chips_per_sample;
  std::size_t block_samples;

  std::size_t blocks() const { return x.size() / block_samples; }

  /// Prompt sums of each 1 ms block for a replica at `phase_chips` at the first sample.
  std::vector<std::complex<double>> block_sums(double phase_chips) const {
    std::vector<std::complex<double>> sums(blocks());
    double chip = std::fmod(phase_chips, gps::kCodeLength_chips);
    if (chip < 0.0) chip += gps::kCodeLength_chips;
    for (std::size_t b = 0; b < sums.size(); ++b) {
      std::complex<float> sum(0.0f, 0.0f);
      const std::size_t first = b * block_samples;
      for (std::size_t n = first; n < first + block_samples; ++n) {
        sum += x[n] * static_cast<float>(code[static_cast<std::size_t>(chip)]);
        chip += chips_per_sample;
        if (chip >= gps::kCodeLength_chips) chip -= gps::kCodeLength_chips;
      }
      sums[b] = std::complex<double>(sum);
    }
    return sums;
  }

  /// A(phi): the square root of the summed block powers.
  double amplitude(double phase_chips) const {
    double power = 0.0;
    for (const auto& s : block_sums(phase_chips)) power += std::norm(s);
    return std::sqrt(power);
  }
};

double chips_per_sample(double doppler_hz, double fs_hz) {
  return gps::kCodeRate_cps * (1.0 + doppler_hz / gps::kL1_Hz) / fs_hz;
}

/// The Doppler error of the prompt block sums (see the header), in Hz.
double doppler_error_hz(const std::vector<std::complex<double>>& sums, double block_s) {
  std::complex<double> acc(0.0, 0.0);
  for (std::size_t k = 1; k < sums.size(); ++k) {
    const std::complex<double> turn = sums[k] * std::conj(sums[k - 1]);
    acc += turn * turn;
  }
  if (std::abs(acc) == 0.0) return 0.0;
  return std::arg(acc) / (4.0 * std::numbers::pi * block_s);
}

double wrapped_chips(double chips) {
  double c = std::fmod(chips, gps::kCodeLength_chips);
  if (c < 0.0) c += gps::kCodeLength_chips;
  return c;
}

}  // namespace

CodePhaseRefiner::CodePhaseRefiner(double sample_rate_hz, double if_hz, CodePhaseRefinementConfig config)
    : fs_hz_(sample_rate_hz), if_hz_(if_hz), cfg_(config) {
  if (!(sample_rate_hz >= gps::kCodeRate_cps))
    throw std::invalid_argument(
        fmt::format("code phase refinement: sample rate {} Hz is below the chip rate", sample_rate_hz));
  if (!(std::abs(if_hz) < sample_rate_hz / 2))
    throw std::invalid_argument(
        fmt::format("code phase refinement: IF {} Hz is not below half the sample rate", if_hz));
  if (!(cfg_.early_late_offset_chips > 0.0 && cfg_.early_late_offset_chips < 1.0))
    throw std::invalid_argument("code phase refinement: early_late_offset_chips must be in (0, 1)");
}

RefinedSignal CodePhaseRefiner::refine(std::span<const Sample> samples, int prn, double code_phase_chips,
                                       double doppler_hz) const {
  const auto block_samples = static_cast<std::size_t>(std::floor(fs_hz_ * gps::kCodePeriod_s));
  if (samples.size() < block_samples)
    throw std::invalid_argument(fmt::format("code phase refinement: {} samples are less than one code period ({})",
                                            samples.size(), block_samples));
  const CaCodeChips& code = ca_code_chips(prn);
  const double block_s = static_cast<double>(block_samples) / fs_hz_;
  RefinedSignal out;
  out.doppler_hz = doppler_hz;
  out.code_phase_chips = wrapped_chips(code_phase_chips);
  Baseband x = wiped_off(samples, if_hz_ + out.doppler_hz, fs_hz_);
  // The Doppler first, at the acquisition's code phase (within a fraction of a chip, so
  // the prompt holds most of the power): the code phase is then refined at the right code rate.
  for (int i = 0; i < cfg_.doppler_iterations && samples.size() >= 2 * block_samples; ++i) {
    const Correlation c{x, code, chips_per_sample(out.doppler_hz, fs_hz_), block_samples};
    out.doppler_hz += doppler_error_hz(c.block_sums(out.code_phase_chips), block_s);
    x = wiped_off(samples, if_hz_ + out.doppler_hz, fs_hz_);
  }
  const Correlation c{x, code, chips_per_sample(out.doppler_hz, fs_hz_), block_samples};
  const double d = cfg_.early_late_offset_chips;
  // g(phi) = (L - E) / (L + E) is zero at the peak's centre. The first step is the ideal
  // triangle's, (1 - d) g; after it, secant steps use the slope g actually has (a peak
  // rounded by the front end's filter is steeper in g, and the triangle's step overshoots).
  const auto balance = [&](double phi) {
    const double early = c.amplitude(phi - d), late = c.amplitude(phi + d);
    return early + late > 0.0 ? (late - early) / (late + early) : 0.0;
  };
  double previous = out.code_phase_chips, g_previous = balance(previous);
  double phase = previous + (1.0 - d) * g_previous;
  for (int i = 1; i <= cfg_.max_code_iterations; ++i) {
    out.code_iterations = i;
    if (std::abs(phase - code_phase_chips) > 1.5) {
      out.reason = fmt::format("the code phase wandered {:.2f} chips from the acquisition's", phase - code_phase_chips);
      return out;
    }
    const double g = balance(phase);
    const double dg = g - g_previous;
    if (std::abs(phase - previous) < kSettled_chips || dg == 0.0) {
      out.converged = true;
      break;
    }
    const double step = std::clamp(-g * (phase - previous) / dg, -0.5, 0.5);
    previous = phase;
    g_previous = g;
    phase += step;
  }
  if (!out.converged) out.reason = fmt::format("no balance of early and late in {} steps", cfg_.max_code_iterations);
  out.code_phase_chips = wrapped_chips(phase);
  out.prompt_amplitude = c.amplitude(phase);
  return out;
}

}  // namespace deepnav
