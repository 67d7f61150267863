#pragma once
// The E1 correlator's kernels (receiver/tracking/e1_correlator.hpp is the interface). A kernel
// gets validated arguments: n > 0, a code step in (0, 1], all three codes present.
#include "receiver/tracking/e1_correlator.hpp"

namespace deepnav::e1_correlator_detail {

/// The definition: double precision, carrier phasor restarted exactly every run of samples.
E1CorrelatorSums correlate_portable(const Sample* samples, int n, const E1CorrelatorSpan& span,
                                    const E1CorrelatorCodes& codes);

}  // namespace deepnav::e1_correlator_detail
