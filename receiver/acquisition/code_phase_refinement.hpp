#pragma once
// Sub-sample code phase and a finer Doppler for a signal the FFT acquisition found, from
// the same samples: what a snapshot position needs (receiver/snapshot_positioner.hpp). The
// acquisition's delay is good to about half a sample (its lag grid, the parabola between
// lags and the stretch of the FFT block, acquisition.hpp): 30-60 m of range at 2.6-4 Msps,
// too coarse for a fix from code phases alone.
//
// Correlation. The samples are wiped off at the carrier (IF + Doppler) and correlated with
// the C/A replica at the code rate the Doppler implies (1.023 MHz (1 + f_D / f_L1)), in
// 1 ms blocks whose powers are summed (a data-bit edge may fall anywhere in the snapshot,
// so no block longer than a code period is coherent); A(phi) is the square root of that
// sum for a replica at code phase phi at the first sample.
//
// Code phase. The peak of A is found where an early and a late replica (phi -+ d) see
// equal amplitudes: for any correlation peak that is symmetric (the triangle rounded by
// the front end's filter and the sampling), that is its centre, unlike a parabola through
// the samples of the peak. The first step, phi += (1 - d) (L - E) / (L + E), is exact for
// the ideal triangle; secant steps on (L - E) / (L + E) follow until they are below 2e-3
// chip (0.6 m).
//
// Doppler. Successive 1 ms prompt correlations B_k turn by 2 pi f_err T; squaring the
// products B_k conj(B_k-1) removes a data-bit flip between them, so
//   f_err = arg(sum_k (B_k conj B_k-1)^2) / (4 pi T)
// is unambiguous within +-250 Hz (the acquisition's refined Doppler is within tens of Hz).
#include <span>
#include <string>

#include "receiver/sources/sample_source.hpp"

namespace deepnav {

struct CodePhaseRefinementConfig {
  double early_late_offset_chips = 0.5;  ///< d: early and late replicas at phi -+ d
  int max_code_iterations = 20;
  int doppler_iterations = 2;  ///< carrier re-wiped at each new Doppler
};

struct RefinedSignal {
  bool converged = false;
  std::string reason;             ///< why not converged
  double code_phase_chips = 0.0;  ///< at the first sample, in [0, 1023)
  double doppler_hz = 0.0;
  int code_iterations = 0;
  double prompt_amplitude = 0.0;  ///< A at the refined code phase (arbitrary units)
};

class CodePhaseRefiner {
 public:
  /// Throws std::invalid_argument for a sample rate below the chip rate or an IF beyond
  /// half the sample rate.
  CodePhaseRefiner(double sample_rate_hz, double if_hz, CodePhaseRefinementConfig config = {});

  /// Refines `prn` from the acquisition's code phase (chips at the first sample) and
  /// Doppler. Needs at least one whole code period of samples (two for the Doppler);
  /// throws std::invalid_argument with fewer or a PRN outside 1..32.
  RefinedSignal refine(std::span<const Sample> samples, int prn, double code_phase_chips, double doppler_hz) const;

 private:
  double fs_hz_;
  double if_hz_;
  CodePhaseRefinementConfig cfg_;
};

}  // namespace deepnav
