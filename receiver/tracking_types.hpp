#pragma once
// The seam between a channel and whoever steers it (DESIGN.md): a channel applies
// NcoCommands and emits CorrelatorEpochs. The scalar loop controller and, later, the
// ultra-tight aiding filter both turn epochs into commands; the channel does not know
// which one is driving it.
#include <complex>
#include <cstdint>

namespace deepnav {

/// Rates for the channel's numerically controlled oscillators from the next sample on.
struct NcoCommand {
  double code_rate_cps = 1.023e6;       ///< code chips per second
  double carrier_doppler_hz = 0.0;      ///< carrier frequency minus the IF
};

/// One integration of one channel: correlator sums and the NCO state at its end.
struct CorrelatorEpoch {
  int prn = 0;
  std::int64_t first_sample = 0;        ///< absolute index of the first sample integrated
  int samples = 0;
  double integration_s = 0.0;
  std::int64_t code_period = 0;         ///< code periods (ms) completed since tracking started, at the end
  std::complex<double> early, prompt, late;  ///< E/P/L at +-spacing/2 chips
  std::complex<double> noise;           ///< a correlator on an unused PRN code: noise power reference
  double carrier_phase_cycles = 0.0;    ///< accumulated carrier NCO phase at the end (Doppler part, cycles)
  double carrier_doppler_hz = 0.0;      ///< NCO Doppler used over this integration
  double code_rate_cps = 0.0;           ///< NCO code rate used over this integration
};

}  // namespace deepnav
