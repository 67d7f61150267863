#pragma once
// Discriminators and loop filters of the scalar tracking loops, and the controller
// that turns a channel's CorrelatorEpochs into NcoCommands.
//
// Carrier: second-order PLL (Costas atan discriminator, insensitive to data bits)
// assisted by a first-order FLL (atan2 of cross and dot products of consecutive
// prompts) during pull-in, in the standard form of Kaplan & Hegarty (Understanding
// GPS, ch. 5): v += T (w0p^2 e_phase + w0f e_freq), f = v + a2 w0p e_phase, with
// w0p = Bn/0.53, a2 = 1.414 and w0f = Bn_fll/0.25. Code: first-order carrier-aided
// DLL, normalised early-minus-late envelope discriminator, gain 4 Bn.
#include <complex>
#include <optional>

#include "receiver/tracking_types.hpp"

namespace deepnav {

/// Costas phase error (cycles), in (-1/4, 1/4].
double costas_phase_error_cycles(const std::complex<double>& prompt);
/// Frequency error (Hz) between two consecutive prompts of integration time t_s, from
/// atan2(cross, dot) of the pair (both of the same data bit sign or the dot test flips them).
double fll_frequency_error_hz(const std::complex<double>& previous, const std::complex<double>& current, double t_s);
/// Normalised early-minus-late envelope code error (chips) for an E-L spacing.
double dll_code_error_chips(const std::complex<double>& early, const std::complex<double>& late, double spacing_chips);

struct LoopBandwidths {
  double pll_hz = 15.0;
  double fll_hz = 10.0;
  double dll_hz = 1.0;
  double dll_spacing_chips = 0.5;  ///< early-late spacing the channel uses
};

class ScalarLoopController {
 public:
  ScalarLoopController(double initial_doppler_hz, LoopBandwidths bandwidths);
  /// The command for the next integration; `use_fll` adds frequency assistance (pull-in).
  NcoCommand update(const CorrelatorEpoch& epoch, bool use_fll);
  void set_bandwidths(const LoopBandwidths& b) { bw_ = b; }
  double doppler_hz() const;

 private:
  LoopBandwidths bw_;
  double velocity_radps_;
  double last_output_hz_;
  std::optional<std::complex<double>> previous_prompt_;
};

}  // namespace deepnav
