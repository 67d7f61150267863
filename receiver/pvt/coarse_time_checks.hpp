#pragma once
// What a coarse-time fix must also be, beyond passing its residual test, to be a fix: at
// a plausible height, below no satellite's horizon, with a time correction the method
// tolerates (CoarseTimeConfig). A wrong set of whole milliseconds that happens to fit
// usually fails one of them.
#include <string>

#include "receiver/pvt/coarse_time_config.hpp"
#include "receiver/pvt/coarse_time_integrity.hpp"

namespace deepnav {

/// Why the place of `fit` (which passed its test) cannot be the receiver's: its height,
/// or a satellite below the horizon there; empty when it can.
std::string implausible_place(const CheckedCoarseTimeFit& fit, const CoarseTimeConfig& config);
/// Why its time correction is not accepted; empty when it is.
std::string time_beyond_tolerance(const CheckedCoarseTimeFit& fit, const CoarseTimeConfig& config);
/// Either of them; empty when `fit` is a fix.
std::string implausibility(const CheckedCoarseTimeFit& fit, const CoarseTimeConfig& config);

}  // namespace deepnav
