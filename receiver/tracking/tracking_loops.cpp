#include "receiver/tracking/tracking_loops.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "signals/gps_constants.hpp"

namespace deepnav {

double costas_phase_error_cycles(const std::complex<double>& p) {
  if (p.real() == 0.0) return 0.0;
  return std::atan(p.imag() / p.real()) / (2.0 * M_PI);
}

double fll_frequency_error_hz(const std::complex<double>& a, const std::complex<double>& b, double t_s) {
  const double dot = a.real() * b.real() + a.imag() * b.imag();
  const double cross = a.real() * b.imag() - a.imag() * b.real();
  // A data bit change between the two flips the pair: the sign of dot removes it.
  const double s = dot < 0.0 ? -1.0 : 1.0;
  return std::atan2(s * cross, s * dot) / (2.0 * M_PI * t_s);
}

double dll_code_error_chips(const std::complex<double>& early, const std::complex<double>& late, double spacing) {
  const double e = std::abs(early), l = std::abs(late);
  if (e + l <= 0.0) return 0.0;
  return (1.0 - 0.5 * spacing) * (e - l) / (e + l);
}

CarrierLoopFilter::CarrierLoopFilter(int order, double pll_hz, double fll_hz, double initial_hz)
    : order_(2), pll_hz_(0.0), fll_hz_(0.0), velocity_radps_(2.0 * M_PI * initial_hz), output_hz_(initial_hz) {
  set_bandwidths(order, pll_hz, fll_hz);
}

void CarrierLoopFilter::set_bandwidths(int order, double pll_hz, double fll_hz) {
  if (order != 2 && order != 3)
    throw std::invalid_argument("carrier loop: PLL order must be 2 or 3, got " + std::to_string(order));
  if (!(pll_hz >= 0.0) || !(fll_hz >= 0.0)) throw std::invalid_argument("carrier loop: bandwidths must be >= 0 Hz");
  order_ = order;
  pll_hz_ = pll_hz;
  fll_hz_ = fll_hz;
}

double CarrierLoopFilter::update(double e_phase_rad, double e_freq_radps, double t) {
  double output_radps = 0.0;
  if (order_ == 2) {
    const double w0p = pll_hz_ / 0.53, w0f = fll_hz_ / 0.25;
    velocity_radps_ += t * (w0p * w0p * e_phase_rad + w0f * e_freq_radps);
    output_radps = velocity_radps_ + 1.414 * w0p * e_phase_rad;
  } else {
    const double w0p = pll_hz_ / 0.7845, w0f = fll_hz_ / 0.53;
    acceleration_radps2_ += t * (w0p * w0p * w0p * e_phase_rad + w0f * w0f * e_freq_radps);
    velocity_radps_ += t * (acceleration_radps2_ + 1.1 * w0p * w0p * e_phase_rad + 1.414 * w0f * e_freq_radps);
    output_radps = velocity_radps_ + 2.4 * w0p * e_phase_rad;
  }
  output_hz_ = output_radps / (2.0 * M_PI);
  return output_hz_;
}

double carrier_aided_code_rate_cps(double carrier_doppler_hz, double code_error_chips, double dll_hz) {
  return gps::kCodeRate_cps * (1.0 + carrier_doppler_hz / gps::kL1_Hz) + 4.0 * dll_hz * code_error_chips;
}

ScalarLoopController::ScalarLoopController(double initial_doppler_hz, int pll_order, LoopBandwidths b)
    : pll_order_(pll_order), bw_(b), carrier_(pll_order, b.pll_hz, b.fll_hz, initial_doppler_hz) {}

void ScalarLoopController::set_bandwidths(const LoopBandwidths& b) {
  carrier_.set_bandwidths(pll_order_, b.pll_hz, b.fll_hz);
  bw_ = b;
}

void ScalarLoopController::reset(double doppler_hz) {
  carrier_ = CarrierLoopFilter(pll_order_, bw_.pll_hz, bw_.fll_hz, doppler_hz);
  previous_prompt_.reset();
}

NcoCommand ScalarLoopController::update(const CorrelatorEpoch& epoch, bool use_fll) {
  const double t = epoch.integration_s;
  const double e_phase_rad = 2.0 * M_PI * costas_phase_error_cycles(epoch.prompt);
  double e_freq_radps = 0.0;
  if (use_fll && previous_prompt_) {
    e_freq_radps = 2.0 * M_PI * fll_frequency_error_hz(*previous_prompt_, epoch.prompt, t);
  }
  previous_prompt_ = epoch.prompt;
  if (use_fll) {
    const double fade = bw_.fll_fade_s > 0.0 ? std::exp(-fll_time_s_ / bw_.fll_fade_s) : 1.0;
    carrier_.set_bandwidths(pll_order_, bw_.pll_hz, bw_.fll_hz * fade);
    fll_time_s_ += t;
  }
  NcoCommand cmd;
  cmd.carrier_doppler_hz = carrier_.update(e_phase_rad, e_freq_radps, t);
  const double e_code = dll_code_error_chips(epoch.early, epoch.late, epoch.spacing_chips);
  cmd.code_rate_cps = carrier_aided_code_rate_cps(cmd.carrier_doppler_hz, e_code, bw_.dll_hz);
  return cmd;
}

}  // namespace deepnav
