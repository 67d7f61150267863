#pragma once
// The correlator alone, timed: how many channel-samples per second one kernel correlates
// on one core, as the receiver calls it.
#include <optional>

#include "receiver/tracking/correlator.hpp"
#include "receiver/tracking/e1_correlator.hpp"

namespace deepnav::bench {

struct CorrelatorThroughput {
  double wall_s = 0.0, cpu_s = 0.0;  ///< of the timed loop (the calling thread's CPU time)
  double channel_samples = 0.0;      ///< samples correlated, summed over the channels
};

/// One kernel: 12 channels, each its own PRN, Doppler and code phase, over the same 1 ms of
/// 4.092 Msps noise, repeated for about a second; `noise_tap`: with the noise correlator
/// (else early, prompt and late only).
CorrelatorThroughput correlator_throughput(CorrelatorKernel kernel, bool noise_tap);

/// The E1 correlator as the Galileo channels run it: 8 channels, each its own PRN, Doppler and
/// code phase, over one 4 ms code period of 4 Msps noise; five pilot taps (very-early to
/// very-late) and the data prompt, with or without the noise pass. `kernel` empty: the
/// double-precision reference (correlate_e1_reference()), what the channels ran before the
/// fixed-point path.
CorrelatorThroughput e1_correlator_throughput(std::optional<CorrelatorKernel> kernel, bool noise_tap);

}  // namespace deepnav::bench
