#pragma once
// The Galileo system offset a range filter with one receiver clock takes off Galileo
// pseudoranges: c (clock of the Galileo measurements - GPS clock), the GGTO plus the
// receiver's own inter-system bias (front-end group delays differ between the E1 and L1 C/A
// signals' spectra). The two-system PVT estimates it at every mixed fix
// (PvtSolution::system_offset_m); both parts are constant over a run (the GGTO drifts by
// nanoseconds a day), so the filter takes the mean of the fixes' estimates.
//
// Its uncertainty: the fixes' scatter over the square root of the number of independent
// fixes, taken as one per `correlation_s` (a fix's errors, multipath and the loops' noise,
// are correlated over seconds), never below `floor_m`. It is common to every Galileo row, so
// the rows add it in quadrature (RangeObservation::offset_sigma_m) rather than as
// independent noise: a conservative weighting, not a state of the filter.
#include <optional>

#include "receiver/pvt/pvt_solver.hpp"

namespace deepnav::aiding {

struct GalileoClockOffsetConfig {
  int min_fixes = 5;            ///< mixed fixes before the offset is used
  double correlation_s = 10.0;  ///< fixes closer than this count as one
  double floor_m = 0.3;         ///< the offset's sigma never goes below this
};

class GalileoClockOffset {
 public:
  explicit GalileoClockOffset(GalileoClockOffsetConfig config = {}) : cfg_(config) {}

  /// A fix at t_s (non-decreasing); only valid two-system fixes count.
  void add(double t_s, const PvtSolution& fix);
  /// The mean offset (m), once min_fixes mixed fixes came in.
  std::optional<double> offset_m() const;
  /// The offset's sigma (m), meaningful once offset_m() has a value.
  double sigma_m() const;
  int fixes() const { return n_; }

 private:
  GalileoClockOffsetConfig cfg_;
  int n_ = 0;
  double mean_m_ = 0.0, m2_ = 0.0;  // Welford's running mean and sum of squared deviations
  double first_t_s_ = 0.0, last_t_s_ = 0.0;
};

}  // namespace deepnav::aiding
