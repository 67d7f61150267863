#pragma once
// Code phase and Doppler of a Galileo E1 signal near an acquisition's coarse cell, found on
// the BOC(1,1) correlation's main peak and never on a side lobe.
//
// The BOC(1,1) autocorrelation is 1 - 3|tau| within half a chip, so its main peak is only
// 2/3 chip wide, and it has two negative side lobes of -1/2 at +-1/2 chip. A search grid whose
// lags are a quarter chip apart may catch the main peak well off its top (down to 0.62 at
// 4 Msps) and a side lobe on its extreme (0.5): the side lobe's power is then only 1.8 dB
// below, and noise can put the grid's largest cell on it. So the coarse cell's code phase and
// the cells half a chip on either side are each searched, in the time domain, over +-1/4
// chip (a window that cannot reach the next lobe half a chip away); the candidate with the
// most power is the main peak (four times a side lobe's power at their extremes), and a
// parabola through its best point and neighbours gives the code phase.
//
// Correlation: the samples, less their mean, are wiped off at IF + Doppler and multiplied
// by the E1-B and E1-C primary codes on the BOC(1,1) subcarrier at the code rate the
// Doppler implies; sums run from code epoch to code epoch, since an E1-B data symbol and an
// E1-C secondary code chip may change sign at each epoch, and the power is
// sum over periods of |B|^2 + |C|^2 (non-coherent across the two components and periods).
// The Doppler is refined first, at the coarse code phase, over +-1 bin in steps of 1/10 bin,
// and again at the main peak once it is found.
#include <span>

#include "receiver/sources/sample_source.hpp"

namespace deepnav {

/// Correlation powers of one code phase and Doppler over a span of samples.
struct E1CorrelationPower {
  double all_periods = 0.0;   ///< sum of |B|^2 + |C|^2 over every (partial) code period
  double full_periods = 0.0;  ///< the same over whole code periods only
  int full_period_count = 0;
};

struct E1RefinedSignal {
  double code_phase_chips = 0.0;  ///< at the first sample, in [0, 4092)
  double doppler_hz = 0.0;
  E1CorrelationPower power;          ///< at the refined code phase and Doppler
  bool moved_off_side_lobe = false;  ///< the coarse cell was half a chip from the main peak
};

class E1CodePhaseRefiner {
 public:
  /// Throws std::invalid_argument for a sample rate below 2.046 MHz or an IF beyond half of it.
  E1CodePhaseRefiner(double sample_rate_hz, double if_hz);

  /// The correlation of `samples` with the E1-B and E1-C codes of `prn` (1..50) at code phase
  /// `code_phase_chips` (at the first sample) and `doppler_hz`.
  E1CorrelationPower correlate(std::span<const Sample> samples, int prn, double code_phase_chips,
                               double doppler_hz) const;

  /// Refines a coarse cell (code phase, Doppler, Doppler bin width) of `prn` (see above).
  E1RefinedSignal refine(std::span<const Sample> samples, int prn, double code_phase_chips, double doppler_hz,
                         double doppler_bin_hz) const;

 private:
  double fs_hz_;
  double if_hz_;
};

}  // namespace deepnav
