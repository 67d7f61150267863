#pragma once
// Discriminators and loop filters of the scalar tracking loops, and the controller
// that turns a channel's CorrelatorEpochs into NcoCommands.
//
// Carrier: Costas atan phase discriminator (insensitive to data bits) driving a 2nd- or
// 3rd-order PLL, assisted during pull-in by an FLL (atan2 of the cross and dot products
// of consecutive prompts), in the standard forms of Kaplan & Hegarty (Understanding GPS,
// 2nd ed., table 5.6 and fig. 5.21), integrators by the rectangular rule:
//   2nd-order PLL + 1st-order FLL:  w0p = Bn/0.53,   a2 = 1.414;   w0f = Bn_f/0.25
//     v += T (w0p^2 e_phi + w0f e_f);              f = v + a2 w0p e_phi
//   3rd-order PLL + 2nd-order FLL:  w0p = Bn/0.7845, a3 = 1.1, b3 = 2.4;  w0f = Bn_f/0.53
//     a += T (w0p^3 e_phi + w0f^2 e_f);  v += T (a + a3 w0p^2 e_phi + 1.414 w0f e_f);
//     f = v + b3 w0p e_phi
// A 2nd-order PLL follows a frequency step with no steady phase error and a Doppler rate
// R with a phase error of 2 pi R / w0p^2; the 3rd-order one follows a Doppler rate too.
// Code: first-order DLL (gain 4 Bn), carrier aided (code Doppler = carrier Doppler
// / 1540), normalised early-minus-late envelope discriminator.
#include <complex>
#include <optional>

#include "receiver/tracking/tracking_types.hpp"

namespace deepnav {

/// Costas phase error (cycles), in (-1/4, 1/4].
double costas_phase_error_cycles(const std::complex<double>& prompt);
/// Frequency error (Hz) between two consecutive prompts of integration time t_s, from
/// atan2(cross, dot) of the pair (a data bit change between them is removed by the sign of dot).
double fll_frequency_error_hz(const std::complex<double>& previous, const std::complex<double>& current, double t_s);
/// Normalised early-minus-late envelope code error (chips) for an E-L spacing; positive
/// when the replica lags the signal (the early tap is the stronger).
double dll_code_error_chips(const std::complex<double>& early, const std::complex<double>& late, double spacing_chips);

/// The carrier loop filter alone: phase (and frequency) errors in, NCO frequency out.
class CarrierLoopFilter {
 public:
  /// order 2 or 3; throws std::invalid_argument otherwise or for a negative bandwidth.
  CarrierLoopFilter(int pll_order, double pll_bandwidth_hz, double fll_bandwidth_hz, double initial_frequency_hz);
  void set_bandwidths(int pll_order, double pll_bandwidth_hz, double fll_bandwidth_hz);
  /// One update after an integration of t_s seconds; frequency error 0 when the FLL is off.
  /// Returns the NCO frequency (Hz) for the next integration.
  double update(double phase_error_rad, double frequency_error_radps, double t_s);
  double frequency_hz() const { return output_hz_; }

 private:
  int order_;
  double pll_hz_, fll_hz_;
  double velocity_radps_;
  double acceleration_radps2_ = 0.0;
  double output_hz_;
};

/// First-order carrier-aided DLL: code rate = nominal (1 + Doppler / f_L1) + 4 Bn error.
double carrier_aided_code_rate_cps(double carrier_doppler_hz, double code_error_chips, double dll_bandwidth_hz);

/// Loop bandwidths of one phase of tracking (pull-in, tracking). The loop order is the
/// receiver's (ReceiverConfig::pll_order), the same in both phases; the DLL's early-late
/// spacing is the channel's (CorrelatorEpoch::spacing_chips).
struct LoopBandwidths {
  double pll_hz = 15.0;
  double fll_hz = 10.0;
  double dll_hz = 1.0;
  /// The FLL assistance fades out with this time constant (counted over the epochs it is
  /// used), so the PLL takes over without the FLL's frequency noise (tens of hertz at
  /// 30 dB-Hz with 1 ms integrations); 0 keeps it at full bandwidth.
  double fll_fade_s = 0.08;
};

/// The scalar receiver's loop: CorrelatorEpoch in, NcoCommand out. The ultra-tight
/// filter replaces exactly this object.
class ScalarLoopController {
 public:
  /// pll_order 2 or 3; throws std::invalid_argument otherwise.
  ScalarLoopController(double initial_doppler_hz, int pll_order, LoopBandwidths bandwidths);
  /// The command for the next integration; `use_fll` adds frequency assistance (pull-in).
  NcoCommand update(const CorrelatorEpoch& epoch, bool use_fll);
  void set_bandwidths(const LoopBandwidths& b);
  /// Restarts the loop at a frequency (an outside filter had the channel until now).
  void reset(double doppler_hz);
  double doppler_hz() const { return carrier_.frequency_hz(); }

 private:
  int pll_order_;
  LoopBandwidths bw_;
  CarrierLoopFilter carrier_;
  std::optional<std::complex<double>> previous_prompt_;
  double fll_time_s_ = 0.0;  ///< time the FLL assistance has been applied
};

}  // namespace deepnav
