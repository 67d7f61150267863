#pragma once
// The receiver's hot path: carrier and code wipe-off of a span of samples against
// early, prompt, late (optionally very-early/very-late) and noise replicas, with
// constant code rate and carrier frequency over the span.
//
// Numerics: the span is cut into runs of at most 1024 samples. Each run restarts the
// carrier phasor and the code index from the exact double-precision phases, so nothing
// drifts however long the span is. Inside a run the carrier is a float phasor advanced
// in 16 parallel lanes and the code index a 11.21 fixed-point accumulator (index error
// below 3e-4 chip at the end of a run); the loops have no data-dependent branches and
// vectorise (AVX-512 / AVX2 clones).
#include <complex>
#include <cstdint>
#include <vector>

#include "receiver/sample_source.hpp"
#include "signals/ca_code.hpp"

namespace deepnav {

struct CorrelatorSums {
  std::complex<double> early, prompt, late;  ///< at +spacing/2, 0, -spacing/2 chips from the prompt
  std::complex<double> very_early, very_late;  ///< at +-very_spacing/2 chips; zero when disabled
  std::complex<double> noise;  ///< prompt timing on an untracked PRN's code: noise reference
};

struct CorrelatorSpan {
  double carrier_phase_cycles = 0.0;   ///< phase of the replica at the first sample (IF + Doppler)
  double carrier_step_cycles = 0.0;    ///< per sample
  double code_phase_chips = 0.0;       ///< prompt code phase at the first sample (any value; taken modulo 1023)
  double code_step_chips = 0.0;        ///< per sample, in (0, 2]
  double spacing_chips = 0.5;          ///< early-late spacing
  double very_spacing_chips = 0.0;     ///< very-early/very-late spacing; 0 disables them
};

/// Instruction-set variants of the code wipe-off kernel; correlate() picks the best one the
/// CPU supports. The AVX variants replace the code-table gather by a lane permutation of
/// one table load when the code step allows it.
enum class CorrelatorKernel { portable, avx2, avx512 };
CorrelatorKernel best_correlator_kernel();
/// The kernels this CPU can run (portable always), for tests and benchmarks.
std::vector<CorrelatorKernel> available_correlator_kernels();

/// Correlator sums over n samples. `noise_code` is the code of a PRN that is not tracked.
/// Sums are in sample units: a noise-free signal of amplitude A aligned with the prompt
/// gives |prompt| = A n. Throws std::invalid_argument for a code step outside (0, 2].
CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& span, const CaCodeChips& code,
                         const CaCodeChips& noise_code);
/// The same with an explicit kernel (must be one of available_correlator_kernels()).
CorrelatorSums correlate(CorrelatorKernel kernel, const Sample* samples, int n, const CorrelatorSpan& span,
                         const CaCodeChips& code, const CaCodeChips& noise_code);

/// The same sums computed sample by sample in double precision, without any of the
/// shortcuts above: the reference the fast path is tested against.
CorrelatorSums correlate_reference(const Sample* samples, int n, const CorrelatorSpan& span, const CaCodeChips& code,
                                   const CaCodeChips& noise_code);

}  // namespace deepnav
