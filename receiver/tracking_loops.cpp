#include "receiver/tracking_loops.hpp"

#include <cmath>

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

ScalarLoopController::ScalarLoopController(double initial_doppler_hz, LoopBandwidths b)
    : bw_(b), velocity_radps_(2.0 * M_PI * initial_doppler_hz), last_output_hz_(initial_doppler_hz) {}

double ScalarLoopController::doppler_hz() const { return last_output_hz_; }

NcoCommand ScalarLoopController::update(const CorrelatorEpoch& epoch, bool use_fll) {
  const double t = epoch.integration_s;
  const double e_phase_rad = 2.0 * M_PI * costas_phase_error_cycles(epoch.prompt);
  double e_freq_radps = 0.0;
  if (use_fll && previous_prompt_) {
    e_freq_radps = 2.0 * M_PI * fll_frequency_error_hz(*previous_prompt_, epoch.prompt, t);
  }
  previous_prompt_ = epoch.prompt;
  const double w0p = bw_.pll_hz / 0.53;
  const double w0f = bw_.fll_hz / 0.25;
  velocity_radps_ += t * (w0p * w0p * e_phase_rad + (use_fll ? w0f * e_freq_radps : 0.0));
  const double output_radps = velocity_radps_ + 1.414 * w0p * e_phase_rad;
  last_output_hz_ = output_radps / (2.0 * M_PI);

  NcoCommand cmd;
  cmd.carrier_doppler_hz = last_output_hz_;
  const double e_code = dll_code_error_chips(epoch.early, epoch.late, bw_.dll_spacing_chips);
  cmd.code_rate_cps = gps::kCodeRate_cps * (1.0 + last_output_hz_ / gps::kL1_Hz) + 4.0 * bw_.dll_hz * e_code;
  return cmd;
}

}  // namespace deepnav
