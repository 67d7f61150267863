#pragma once
// The seam between a channel and whoever steers it (docs/architecture.md): a channel applies
// NcoCommands and emits CorrelatorEpochs. Its own loops and the ultra-tight aiding filter
// both turn epochs into commands, as ChannelControllers (channel_controller.hpp); the
// channel does not know which one is driving it.
#include <complex>
#include <cstdint>
#include <optional>

#include "signals/gps_constants.hpp"

namespace deepnav {

/// Rates for the channel's numerically controlled oscillators from the next sample on.
/// The carrier NCO runs at IF + carrier_doppler_hz; the IF belongs to the front end and is
/// part of the channel's configuration, so an outside filter deals in Doppler only.
struct NcoCommand {
  double code_rate_cps = 1.023e6;   ///< code chips per second
  double carrier_doppler_hz = 0.0;  ///< carrier frequency minus the IF
  /// One-off jumps applied at the next sample, before the new rates: a filter that
  /// estimates the phase errors directly (vector/ultra-tight tracking) corrects them here
  /// instead of through a rate. Positive advances the replica.
  std::optional<double> code_phase_correction_chips;
  std::optional<double> carrier_phase_correction_cycles;
};

/// Code periods from the start of the data bit that code period `period` falls in, given the
/// code period at which some bit starts (0..19; for periods before that edge too).
inline int code_periods_into_bit(std::int64_t period, std::int64_t bit_edge_period) {
  constexpr std::int64_t kBit = 20;  // code periods per LNAV data bit
  return static_cast<int>(((period - bit_edge_period) % kBit + kBit) % kBit);
}

/// The code of a channel's noise correlator: the next PRN. At zero lag two C/A codes
/// correlate to exactly -1/1023 (the G1 sequence cancels and two shifts of G2 are a third
/// shift of an m-sequence), so the tracked signal, which the noise correlator sees with the
/// same code timing and carrier, leaks only 1e-6 of its power into the noise estimate.
inline int noise_reference_prn(int prn) { return prn % gps::kMaxPrn + 1; }

/// One integration of one channel: correlator sums and the NCO state at its end.
/// Correlator sums are in sample units (a noise-free aligned signal of amplitude A over
/// n samples gives |prompt| = A n); the lock flags and C/N0 include this integration.
struct CorrelatorEpoch {
  int prn = 0;
  int channel = 0;                ///< the owner's channel number (ChannelStart::channel)
  std::int64_t first_sample = 0;  ///< absolute index of the first sample integrated
  int samples = 0;
  double integration_s = 0.0;
  std::int64_t code_period = 0;              ///< code periods (ms) completed since tracking started, at the end
  std::complex<double> early, prompt, late;  ///< E/P/L at +-spacing_chips/2 chips
  /// Early-late spacing the taps were taken at: the channel's TrackingConfig::spacing_chips,
  /// the one setting of it. Every code discriminator reads it from here.
  double spacing_chips = 0.0;
  std::complex<double> very_early, very_late;  ///< at +-very_spacing/2 chips; zero when not configured
  std::complex<double> noise;                  ///< a correlator on an unused PRN code: noise power reference
  int noise_samples = 0;              ///< samples `noise` covers (the integration's first code period; 0: none)
  double code_phase_chips = 0.0;      ///< prompt code phase at the end, [0, 1023) (0 right after a period)
  double carrier_phase_cycles = 0.0;  ///< accumulated carrier NCO phase at the end (Doppler part, cycles)
  double carrier_doppler_hz = 0.0;    ///< NCO Doppler used over this integration
  double code_rate_cps = 0.0;         ///< NCO code rate used over this integration
  double cn0_dbhz = 0.0;              ///< estimate over the lock detector's window (0 until it is full)
  bool pll_lock = false;              ///< carrier phase lock (with hysteresis)
  bool code_lock = false;             ///< C/N0 above the code-lock threshold (with hysteresis)
  bool bit_synced = false;            ///< data-bit edges known; integrations now end on them
};

/// One data bit from the prompt, once the bits are synchronised: the sum of the prompt
/// integrations over the bit's 20 code periods.
struct PromptBit {
  double soft = 0.0;              ///< in-phase sum (sign = bit, up to the Costas ambiguity)
  std::int64_t first_sample = 0;  ///< absolute sample index at which the bit starts
  std::int64_t code_period = 0;   ///< channel code-period count at the bit start (see CorrelatorEpoch::code_period)
};

}  // namespace deepnav
