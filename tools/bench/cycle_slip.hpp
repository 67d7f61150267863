#pragma once
// Where a tracking channel's carrier phase first slips against the truth: the weak-signal
// threshold benchmark's phase-lock criterion.
#include <utility>
#include <vector>

namespace deepnav::bench {

/// Linear interpolation in a time-sorted series of (t, value); the end values beyond it.
double interpolate(const std::vector<std::pair<double, double>>& series, double t);

/// Time of the first cycle slip of a channel: its NCO phase minus the true carrier phase
/// (either sign convention; the one that stays constant is used) moves by more than 0.35
/// cycle within 0.2 s. The end of tracking when there is none. Both series are (t, cycles),
/// time-sorted.
double first_cycle_slip_s(const std::vector<std::pair<double, double>>& nco,
                          const std::vector<std::pair<double, double>>& truth);

}  // namespace deepnav::bench
