#pragma once
// What a Galileo E1 tracking channel emits: one E1CorrelatorEpoch per integration (pilot
// taps, data prompt, NCO state, lock flags) carrying the E1-B symbols of the code periods it
// covers. The counterpart of CorrelatorEpoch/PromptBit for GPS (tracking_types.hpp); the
// channel is steered by the same NcoCommand.
#include <complex>
#include <cstdint>
#include <vector>

#include "signals/satellite_id.hpp"

namespace deepnav {

enum class E1ChannelState {
  pull_in,         ///< FLL-assisted Costas loop on 4 ms pilot prompts
  secondary_sync,  ///< searching the CS25 phase on the pilot prompts
  tracking,        ///< secondary code wiped: pure PLL on longer pilot integrations
  lost,
};

/// One I/NAV symbol: the in-phase E1-B prompt of one 4 ms code period.
struct E1bSymbol {
  /// Signal level of the symbol (sample units). With polarity_known, positive is logic 0
  /// (ICD Table 11); before that its sign is the Costas loop's guess.
  double soft = 0.0;
  std::int64_t first_sample = 0;  ///< absolute sample index at which the symbol's code period starts
  std::int64_t code_period = 0;   ///< channel code-period count at that start (4 ms each)
  bool polarity_known = false;    ///< the pilot, free of data, fixed the carrier phase's sign
};

/// One integration of an E1 channel. Sums are in sample units (a noise-free BOC(1,1) pilot of
/// amplitude A aligned with the prompt over n samples gives |prompt| = A n).
struct E1CorrelatorEpoch {
  SatelliteId satellite;
  int channel = 0;                ///< the owner's channel number
  std::int64_t first_sample = 0;  ///< absolute index of the first sample integrated
  int samples = 0;
  double integration_s = 0.0;
  std::int64_t code_period = 0;  ///< code periods (4 ms) completed since tracking started, at the end
  /// Pilot (E1-C) taps, secondary code wiped once synchronised (then the prompt is, locked,
  /// positive real), at +very/2, +spacing/2, 0, -spacing/2, -very/2 chips.
  std::complex<double> very_early, early, prompt, late, very_late;
  double spacing_chips = 0.0;
  double very_spacing_chips = 0.0;
  std::complex<double> data_prompt;  ///< E1-B prompt of the integration's last code period
  std::complex<double> noise;        ///< noise reference correlator over the integration
  int noise_samples = 0;
  double code_phase_chips = 0.0;      ///< prompt code phase at the end, [0, 4092)
  double carrier_phase_cycles = 0.0;  ///< accumulated carrier NCO phase at the end (Doppler part)
  double carrier_doppler_hz = 0.0;    ///< NCO Doppler used over this integration
  double code_rate_cps = 0.0;         ///< NCO code rate used over this integration
  /// C/N0 of the whole E1 signal, estimated on the pilot (0 until the window is full).
  double cn0_dbhz = 0.0;
  bool pll_lock = false;
  bool code_lock = false;
  E1ChannelState state = E1ChannelState::pull_in;  ///< the channel's state after this epoch
  bool secondary_synced = false;                   ///< the prompt taps above are secondary-code wiped
  std::vector<E1bSymbol> symbols;                  ///< one per code period integrated, in order
};

}  // namespace deepnav
