#pragma once
// The scalar loops of a Galileo E1 channel: E1CorrelatorEpoch in, NcoCommand out (the
// counterpart of ScalarLoopController, reusing its CarrierLoopFilter and FLL discriminator).
//
// Carrier: during pull-in and secondary-code search the pilot prompts still carry CS25's
// signs, so the PLL uses the Costas discriminator with FLL assistance (fading out as for GPS);
// once the channel wipes the secondary code the pilot carries no data and the PLL uses the
// full atan2 discriminator (+-1/2 cycle, no half-cycle ambiguity) on longer integrations, with
// its own bandwidths.
// Code: carrier-aided first-order DLL on the pilot's early-late envelope with the BOC(1,1)
// discriminator below.
#include <complex>
#include <optional>

#include "receiver/tracking/e1_tracking_types.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "receiver/tracking/tracking_types.hpp"

namespace deepnav {

/// Phase error (cycles, in (-1/2, 1/2]) of a data-free, secondary-wiped pilot prompt.
double pilot_phase_error_cycles(const std::complex<double>& prompt);

/// Normalised early-minus-late envelope code error (chips) on the BOC(1,1) main peak, for an
/// E-L spacing below 2/3 chip; positive when the replica lags. On R(t) = 1 - 3|t| the taps
/// read 1 - 3d/2 +- 3e, so e = (1/3 - d/2) (E - L) / (E + L), exact while |e| <= d/2; beyond
/// that (up to the zero crossing at 1/3 chip) it keeps the right sign and under-reads.
double boc11_dll_code_error_chips(const std::complex<double>& early, const std::complex<double>& late,
                                  double spacing_chips);

struct E1LoopSettings {
  int pll_order = 2;  ///< 2 or 3
  /// 4 ms Costas phase with FLL assistance, before the secondary code is wiped.
  LoopBandwidths pull_in{15.0, 10.0, 1.0, 0.2};
  /// Pure PLL on the wiped pilot (no FLL).
  LoopBandwidths tracking{10.0, 0.0, 0.5, 0.0};
};

class E1LoopController {
 public:
  /// Throws std::invalid_argument for a PLL order other than 2 or 3.
  E1LoopController(double initial_doppler_hz, E1LoopSettings settings = {});
  /// The command for the next integration.
  NcoCommand update(const E1CorrelatorEpoch& epoch);
  /// An outside filter took the integration (a secondary-wiped one): restart the loop at the
  /// NCO Doppler it left, with the tracking bandwidths, so it can take the channel back there.
  void follow(const E1CorrelatorEpoch& epoch);
  double doppler_hz() const { return carrier_.frequency_hz(); }

 private:
  E1LoopSettings s_;
  CarrierLoopFilter carrier_;
  std::optional<std::complex<double>> previous_prompt_;
  double fll_time_s_ = 0.0;
  bool tracking_bandwidths_ = false;
};

}  // namespace deepnav
