#pragma once
// The fixed-point correlation every correlator runs (receiver/tracking/correlator.hpp gives
// its numerics): kernel choice, carrier table, runs of kRun samples restarted from the exact
// phases. Code positions, the code step and the tap spacings are in table entries
// (receiver/tracking/padded_code_table.hpp): C/A chips, or E1 BOC(1,1) half-chips.
#include "receiver/tracking/correlator.hpp"
#include "receiver/tracking/padded_code_table.hpp"

namespace deepnav::correlator_detail {

/// `span` in table entries: code_phase_chips, code_step_chips (in (0, 2]), spacing_chips and
/// very_spacing_chips are read as entries of `code` and `noise` (same period).
CorrelatorSums correlate_padded(CorrelatorKernel kernel, const CorrelatorInput& input, int n,
                                const CorrelatorSpan& span, const PaddedCode& code, const PaddedCode& noise);

}  // namespace deepnav::correlator_detail
