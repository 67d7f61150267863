#include "receiver/acquisition/e1_code_phase_refinement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/galileo_constants.hpp"

namespace deepnav {
namespace {

using galileo::kE1CodeLength_chips;

/// Half-width of the search around each candidate and its step (chips).
constexpr double kCandidateHalfWidth_chips = 0.25;
constexpr double kCandidateStep_chips = 1.0 / 32.0;
/// The side lobes' offset from the main peak (chips).
constexpr double kSideLobeOffset_chips = 0.5;

double wrapped_chips(double chips) {
  double c = std::fmod(chips, static_cast<double>(kE1CodeLength_chips));
  if (c < 0.0) c += kE1CodeLength_chips;
  return c;
}

std::complex<double> sample_mean(std::span<const Sample> x) {
  std::complex<double> sum = 0.0;
  for (const auto& s : x) sum += std::complex<double>(s.real(), s.imag());
  return x.empty() ? sum : sum / static_cast<double>(x.size());
}

/// Both codes of a PRN, and the samples' mean, for repeated correlations.
struct E1Correlator {
  std::span<const Sample> x;
  std::complex<double> mean;
  const galileo::E1CodeChips& b;
  const galileo::E1CodeChips& c;
  double fs_hz, if_hz;

  E1CorrelationPower power(double code_phase_chips, double doppler_hz) const {
    const double w = -2.0 * std::numbers::pi * (if_hz + doppler_hz) / fs_hz;
    const std::complex<double> step = std::polar(1.0, w);
    std::complex<double> rot(1.0, 0.0);
    const double chips_per_sample = galileo::kE1CodeRate_cps * (1.0 + doppler_hz / galileo::kE1_Hz) / fs_hz;
    const double full_length = kE1CodeLength_chips / chips_per_sample;
    double phase = wrapped_chips(code_phase_chips);
    std::complex<double> sum_b = 0.0, sum_c = 0.0;
    std::size_t period_start = 0;
    E1CorrelationPower out;
    const auto close_period = [&](std::size_t end, bool first) {
      const double p = std::norm(sum_b) + std::norm(sum_c);
      out.all_periods += p;
      // Whole periods: not the first (it starts wherever the samples do) and of full length.
      if (!first && static_cast<double>(end - period_start) >= full_length - 1.0) {
        out.full_periods += p;
        ++out.full_period_count;
      }
      sum_b = sum_c = 0.0;
      period_start = end;
    };
    bool first = true;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const auto chip = static_cast<std::size_t>(phase);
      const double subcarrier = phase - static_cast<double>(chip) < 0.5 ? 1.0 : -1.0;
      const std::complex<double> z = (std::complex<double>(x[k].real(), x[k].imag()) - mean) * rot;
      sum_b += z * (subcarrier * b[chip]);
      sum_c += z * (subcarrier * c[chip]);
      rot *= step;
      if ((k & 1023u) == 1023u) rot /= std::abs(rot);  // keep the recursion on the unit circle
      phase += chips_per_sample;
      if (phase >= kE1CodeLength_chips) {
        phase -= kE1CodeLength_chips;
        close_period(k + 1, first);
        first = false;
      }
    }
    if (period_start < x.size()) {
      const double p = std::norm(sum_b) + std::norm(sum_c);
      out.all_periods += p;  // the last, partial period
    }
    return out;
  }
};

/// Vertex offset (in steps, within +-1/2) of a parabola through y(-1), y(0), y(+1).
double parabola_offset(double ym, double y0, double yp) {
  const double curvature = ym - 2.0 * y0 + yp;
  return curvature < 0.0 ? std::clamp(0.5 * (ym - yp) / curvature, -0.5, 0.5) : 0.0;
}

/// The Doppler of most power at a code phase: +-1 bin around the coarse one in tenths of a
/// bin, then a parabola.
double fine_doppler(const E1Correlator& corr, double code_phase_chips, double coarse_hz, double bin_hz) {
  constexpr int kFineSteps = 10;
  const double fine_step = bin_hz / kFineSteps;
  std::array<double, 2 * kFineSteps + 1> power{};
  const auto at = [&](int i) -> double& { return power[static_cast<std::size_t>(i + kFineSteps)]; };
  int best = 0;
  for (int i = -kFineSteps; i <= kFineSteps; ++i) {
    at(i) = corr.power(code_phase_chips, coarse_hz + i * fine_step).all_periods;
    if (at(i) > at(best)) best = i;
  }
  double f = coarse_hz + best * fine_step;
  if (best > -kFineSteps && best < kFineSteps) f += parabola_offset(at(best - 1), at(best), at(best + 1)) * fine_step;
  return f;
}

}  // namespace

E1CodePhaseRefiner::E1CodePhaseRefiner(double sample_rate_hz, double if_hz) : fs_hz_(sample_rate_hz), if_hz_(if_hz) {
  if (!(sample_rate_hz >= 2.0 * galileo::kE1CodeRate_cps))
    throw std::invalid_argument(fmt::format(
        "E1 code phase refinement: sample rate {} Hz is below two samples per chip (2.046 MHz)", sample_rate_hz));
  if (!(std::abs(if_hz) < sample_rate_hz / 2))
    throw std::invalid_argument(
        fmt::format("E1 code phase refinement: IF {} Hz is not below half the sample rate", if_hz));
}

E1CorrelationPower E1CodePhaseRefiner::correlate(std::span<const Sample> samples, int prn, double code_phase_chips,
                                                 double doppler_hz) const {
  const E1Correlator corr{
      samples, sample_mean(samples), galileo::e1b_code_chips(prn), galileo::e1c_code_chips(prn), fs_hz_, if_hz_};
  return corr.power(code_phase_chips, doppler_hz);
}

E1RefinedSignal E1CodePhaseRefiner::refine(std::span<const Sample> samples, int prn, double code_phase_chips,
                                           double doppler_hz, double doppler_bin_hz) const {
  if (samples.empty()) throw std::invalid_argument("E1 code phase refinement: no samples");
  const E1Correlator corr{
      samples, sample_mean(samples), galileo::e1b_code_chips(prn), galileo::e1c_code_chips(prn), fs_hz_, if_hz_};
  E1RefinedSignal out;
  out.doppler_hz = fine_doppler(corr, code_phase_chips, doppler_hz, doppler_bin_hz);

  // Code phase: the coarse cell and the cells half a chip on either side, each searched
  // over +-1/4 chip; the one with the most power holds the main peak.
  const int half_steps = static_cast<int>(std::lround(kCandidateHalfWidth_chips / kCandidateStep_chips));
  double best_power = -1.0, best_phase = code_phase_chips;
  int best_candidate = 0;
  for (int candidate = -1; candidate <= 1; ++candidate) {
    const double centre = code_phase_chips + candidate * kSideLobeOffset_chips;
    for (int j = -half_steps; j <= half_steps; ++j) {
      const double phase = centre + j * kCandidateStep_chips;
      const double p = corr.power(phase, out.doppler_hz).all_periods;
      if (p > best_power) {
        best_power = p;
        best_phase = phase;
        best_candidate = candidate;
      }
    }
  }
  const double pm = corr.power(best_phase - kCandidateStep_chips, out.doppler_hz).all_periods;
  const double pp = corr.power(best_phase + kCandidateStep_chips, out.doppler_hz).all_periods;
  best_phase += parabola_offset(pm, best_power, pp) * kCandidateStep_chips;
  out.code_phase_chips = wrapped_chips(best_phase);
  out.moved_off_side_lobe = best_candidate != 0;
  // Again at the main peak: off it (on a side lobe, a quarter of the power) the first pass
  // was noisier.
  out.doppler_hz = fine_doppler(corr, out.code_phase_chips, doppler_hz, doppler_bin_hz);
  out.power = corr.power(out.code_phase_chips, out.doppler_hz);
  return out;
}

}  // namespace deepnav
