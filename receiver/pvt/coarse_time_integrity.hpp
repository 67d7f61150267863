#pragma once
// The residual test of a coarse-time fit, and what it does on a detection: find the
// satellite whose whole milliseconds are wrong, repair or exclude it (RAIM-like fault
// detection and exclusion, receiver/pvt/raim.hpp, with five unknowns instead of four).
//
// Detection: the weighted sum of squared residuals r' W r is chi-square with n - 5
// degrees of freedom when each pseudorange error is zero-mean Gaussian with its modelled
// sigma; a fault is declared above the quantile at the false-alarm probability (Boost.Math,
// chi_square_threshold). It needs 6 satellites, and a fault can be told apart from the
// others only with 7 or more: with one degree of freedom every standardised residual has
// the same size.
//
// A whole millisecond wrong by one puts 300 km into one pseudorange: nothing that noise
// explains. The satellite with the largest standardised residual (raim.hpp) is excluded
// and the rest fitted and tested again, up to `max_exclusions` times while 6 remain. Once
// the rest passes, each excluded satellite's whole milliseconds are taken again from that
// fix (which knows its range to metres) and it is put back if it then passes with the
// rest: a repaired integer. One that still fails stays excluded (a bad measurement, not a
// wrong integer).
#include <map>
#include <vector>

#include "receiver/pvt/coarse_time_fit.hpp"
#include "receiver/pvt/raim.hpp"

namespace deepnav {

struct CoarseTimeIntegrityConfig {
  double false_alarm_probability = 1e-3;  ///< of the residual test, per test
  int max_exclusions = 2;                 ///< satellites excluded at most
  int max_iterations = 20;                ///< Gauss-Newton iterations per fit
};

/// Residual test of a fit with H of n rows and 5 columns (n >= 6): the statistic, its
/// chi-square bound with n - 5 degrees of freedom and the standardised residuals.
ResidualTest coarse_time_residual_test(const CoarseTimeFit& fit, double false_alarm_probability);

struct CheckedCoarseTimeFit {
  bool passed = false;
  std::string reason;  ///< why not passed
  CoarseTimeFit fit;   ///< of `used`, rows in its order
  std::vector<CoarseTimeSatellite> used;
  std::vector<int> whole_ms;       ///< of `used`
  std::vector<int> excluded_prns;  ///< in the order found
  std::map<int, int> repaired_ms;  ///< PRN -> change of its whole milliseconds
  ResidualTest test;               ///< the last test (dof 0: none ran)
};

/// Fits from `start` with the whole milliseconds `ms` (resolve_whole_milliseconds) and
/// runs the test, excluding and repairing as above.
CheckedCoarseTimeFit checked_coarse_time_fit(const std::vector<CoarseTimeSatellite>& satellites,
                                             const WholeMilliseconds& ms, const CoarseTimeContext& context,
                                             const CoarseTimeState& start, const CoarseTimeIntegrityConfig& config);

}  // namespace deepnav
