#pragma once
// The Galileo E1 correlator bank: carrier wipe-off of a span of samples and correlation
// against BOC(1,1) replicas of the E1-C (pilot) primary code at five delays (very early,
// early, prompt, late, very late), of the E1-B (data) primary code at the prompt and of an
// untracked PRN's pilot code (the noise reference for the C/N0 estimate), with constant code
// rate and carrier frequency over the span.
//
// The replicas are BOC(1,1) (sc_a alone): against the CBOC(6,1,1/11) signal it keeps the
// alpha^2 = 10/11 of each component's power that lies on sc_a (sc_b's six cycles cancel over
// either half of sc_a), at the cost of only 0.4 dB and with a replica of two levels.
//
// The numerics are the C/A correlator's (receiver/tracking/correlator.hpp), on a code table
// of 8184 half-chips: BOC(1,1) is a code of twice the chip rate whose half-chips are c, -c.
// So the same kernels (portable, AVX2, AVX-512, NEON) run it, bit-exact with one another:
// one pass correlates the pilot at five delays and the data code at the prompt (the C/A
// kernel's noise slot), a second pass, only when the noise tap is asked for, the noise
// reference at the prompt. correlate_e1_reference() is the double-precision truth.
#include <complex>

#include "receiver/sources/sample_source.hpp"
#include "receiver/tracking/correlator.hpp"
#include "signals/galileo/e1_codes.hpp"

namespace deepnav {

struct E1CorrelatorSums {
  /// Pilot (E1-C) taps at +very/2, +spacing/2, 0, -spacing/2, -very/2 chips from the prompt.
  std::complex<double> very_early, early, prompt, late, very_late;
  std::complex<double> data_prompt;  ///< E1-B code at the prompt
  std::complex<double> noise;        ///< prompt timing on an untracked PRN's pilot code; zero when off
};

struct E1CorrelatorSpan {
  double carrier_phase_cycles = 0.0;  ///< replica phase at the first sample (IF + Doppler)
  double carrier_step_cycles = 0.0;   ///< per sample
  double code_phase_chips = 0.0;      ///< prompt code phase at the first sample (taken modulo 4092)
  double code_step_chips = 0.0;       ///< per sample, in (0, 1]: at least two samples per chip for BOC(1,1)
  double spacing_chips = 0.2;         ///< early-late spacing
  double very_spacing_chips = 1.0;    ///< very-early/very-late spacing (1: the +-0.5 chip side peaks); 0: off
  bool noise_tap = true;              ///< without it E1CorrelatorSums::noise is zero (and its pass is skipped)
  /// As CorrelatorSpan::magnitude_bits: bits of the largest |I| or |Q| of the samples (or of a
  /// block holding them); -1: scanned here.
  int magnitude_bits = -1;
};

/// The three codes a channel correlates with.
struct E1CorrelatorCodes {
  const galileo::E1CodeChips* pilot = nullptr;  ///< E1-C of the tracked PRN
  const galileo::E1CodeChips* data = nullptr;   ///< E1-B of the tracked PRN
  const galileo::E1CodeChips* noise = nullptr;  ///< E1-C of a PRN that is not tracked
};

/// Correlator sums over n samples, in sample units: a noise-free BOC(1,1) pilot of amplitude
/// A aligned with the prompt gives |prompt| = A n (to the carrier table's 0.2 %). Runs the
/// kernel best_correlator_kernel() picks, or the one named. Throws std::invalid_argument for a
/// code step outside (0, 1] or a missing code.
E1CorrelatorSums correlate_e1(const CorrelatorInput& input, int n, const E1CorrelatorSpan& span,
                              const E1CorrelatorCodes& codes);
E1CorrelatorSums correlate_e1(CorrelatorKernel kernel, const CorrelatorInput& input, int n,
                              const E1CorrelatorSpan& span, const E1CorrelatorCodes& codes);

/// The same sums sample by sample in double precision with an exact carrier phasor: the
/// reference the fixed-point path is tested against.
E1CorrelatorSums correlate_e1_reference(const Sample* samples, int n, const E1CorrelatorSpan& span,
                                        const E1CorrelatorCodes& codes);

/// The BOC(1,1) replica level (+1/-1) of `code` at `chip_phase` (any real, modulo 4092).
double boc11_level(const galileo::E1CodeChips& code, double chip_phase);

}  // namespace deepnav
