#pragma once
// The receiver's hot path: carrier and code wipe-off of a span of samples against
// early, prompt, late and noise replicas, with constant code rate and carrier
// frequency over the span. The carrier is a phasor advanced in 16 parallel lanes
// (exact double-precision start, float recursion), the code index a 32.32 fixed-point
// accumulator, so the loops vectorise.
#include <complex>
#include <cstdint>
#include <span>

#include "receiver/sample_source.hpp"
#include "signals/ca_code.hpp"

namespace deepnav {

struct CorrelatorSums {
  std::complex<double> early, prompt, late, noise;
};

struct CorrelatorSpan {
  double carrier_phase_cycles = 0.0;   ///< phase of the replica at the first sample (IF + Doppler)
  double carrier_step_cycles = 0.0;    ///< per sample
  double code_phase_chips = 0.0;       ///< prompt code phase at the first sample, in [0, 1023)
  double code_step_chips = 0.0;        ///< per sample
  double spacing_chips = 0.5;          ///< early-late spacing
};

/// Sums over n samples; `noise_code` is the code of a PRN that is not tracked.
CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& span, const CaCodeChips& code,
                         const CaCodeChips& noise_code);

}  // namespace deepnav
