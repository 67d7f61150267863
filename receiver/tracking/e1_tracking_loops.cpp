#include "receiver/tracking/e1_tracking_loops.hpp"

#include <cmath>

namespace deepnav {

double pilot_phase_error_cycles(const std::complex<double>& p) {
  if (p == std::complex<double>()) return 0.0;
  return std::atan2(p.imag(), p.real()) / (2.0 * M_PI);
}

double boc11_dll_code_error_chips(const std::complex<double>& early, const std::complex<double>& late, double spacing) {
  const double e = std::abs(early), l = std::abs(late);
  if (e + l <= 0.0) return 0.0;
  return (1.0 / 3.0 - 0.5 * spacing) * (e - l) / (e + l);
}

E1LoopController::E1LoopController(double initial_doppler_hz, E1LoopSettings settings)
    : s_(settings),
      carrier_(settings.pll_order, settings.pull_in.pll_hz, settings.pull_in.fll_hz, initial_doppler_hz) {}

void E1LoopController::follow(const E1CorrelatorEpoch& e) {
  carrier_ = CarrierLoopFilter(s_.pll_order, s_.tracking.pll_hz, 0.0, e.carrier_doppler_hz);
  tracking_bandwidths_ = true;
  previous_prompt_ = e.prompt;
}

NcoCommand E1LoopController::update(const E1CorrelatorEpoch& e) {
  const double t = e.integration_s;
  const bool pull_in = e.state == E1ChannelState::pull_in;
  double e_phase_cycles = 0.0;
  if (e.secondary_synced) {
    if (!tracking_bandwidths_) {
      carrier_.set_bandwidths(s_.pll_order, s_.tracking.pll_hz, 0.0);
      tracking_bandwidths_ = true;
    }
    e_phase_cycles = pilot_phase_error_cycles(e.prompt);
  } else {
    e_phase_cycles = costas_phase_error_cycles(e.prompt);
  }
  double e_freq_radps = 0.0;
  if (pull_in) {
    if (previous_prompt_) e_freq_radps = 2.0 * M_PI * fll_frequency_error_hz(*previous_prompt_, e.prompt, t);
    const double fade = s_.pull_in.fll_fade_s > 0.0 ? std::exp(-fll_time_s_ / s_.pull_in.fll_fade_s) : 1.0;
    carrier_.set_bandwidths(s_.pll_order, s_.pull_in.pll_hz, s_.pull_in.fll_hz * fade);
    fll_time_s_ += t;
  } else if (!e.secondary_synced) {
    carrier_.set_bandwidths(s_.pll_order, s_.pull_in.pll_hz, 0.0);
  }
  previous_prompt_ = e.prompt;
  NcoCommand cmd;
  cmd.carrier_doppler_hz = carrier_.update(2.0 * M_PI * e_phase_cycles, e_freq_radps, t);
  const double dll_hz = e.secondary_synced ? s_.tracking.dll_hz : s_.pull_in.dll_hz;
  const double e_code = boc11_dll_code_error_chips(e.early, e.late, e.spacing_chips);
  cmd.code_rate_cps = carrier_aided_code_rate_cps(cmd.carrier_doppler_hz, e_code, dll_hz);
  return cmd;
}

}  // namespace deepnav
