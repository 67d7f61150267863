#pragma once
// Watches the pseudorange residuals for a troposphere model that does not match the
// signal. A zenith delay error z adds z * m(el) to every satellite's residual (m: the
// receiver's mapping function); per epoch z is fitted by weighted least squares with the
// position and clock errors as nuisances (only the part of m(el) they cannot take tells),
// and over a window of epochs the fits are combined. The residuals are the scalar PVT's
// (post-fit) in scalar, loose and tight mode, and the ultra-tight discriminator
// measurements' against the filter in ultra-tight mode (whose steered channels' own
// pseudoranges only echo the filter's prediction).
//
// A standard atmosphere is wrong by centimetres to a decimetre or two at the zenith; a
// model delay 1.5 m larger than the signal's means the signal has none (IF from a
// generator without troposphere: the fit reads -1.9 to -2.3 m). The test is one-sided:
// reflected and non-line-of-sight signals add delay, most at low elevation, and read
// mostly as the opposite sign (suburban world: +1.1 to +1.2 m, once -1.06 m).
// The aided filter then takes its zenith troposphere state (aided_navigator.hpp): without
// it, the tight and ultra-tight filters turn the model's elevation-dependent error, and
// its rate in every Doppler and carrier row, into metres of height (measured on the
// aircraft circle without troposphere in the signal: ultra-tight 0.72 m horizontal, 6.8 m
// 3-D, against 0.12 m and 1.0 m with the state).
#include <Eigen/Core>
#include <deque>
#include <map>
#include <vector>

#include "receiver/pvt_solver.hpp"
#include "receiver/range_weight.hpp"

namespace deepnav::aiding {

struct TroposphereMismatchConfig {
  double threshold_zenith_m = 1.5;  ///< model over the signal by this at the zenith: a mismatch
  int window_fixes = 30;            ///< fixes combined
  int min_fixes = 20;               ///< before any verdict
};

/// One satellite's pseudorange residual (measured minus predicted) at an epoch.
struct RangeResidual {
  Eigen::Vector3d los = Eigen::Vector3d::UnitZ();  ///< unit line of sight, any frame (the same for an epoch)
  double elevation_rad = 0.0;
  double cn0_dbhz = 45.0;
  double residual_m = 0.0;
};

/// A valid fix's residuals (look angles from the fix; `cn0_dbhz` per PRN).
std::vector<RangeResidual> fix_residuals(const PvtSolution& fix, const std::map<int, double>& cn0_dbhz);

class TroposphereMismatchDetector {
 public:
  explicit TroposphereMismatchDetector(TroposphereMismatchConfig config = {}) : cfg_(config) {}
  /// One epoch's residuals, weighted by `weights` (the PVT's model).
  void add(const std::vector<RangeResidual>& epoch, const RangeErrorModel& weights);
  /// The combined zenith error estimate over the window (m; 0 before min_fixes).
  double zenith_error_m() const;
  bool mismatch() const;

 private:
  struct FixTerm {
    double information = 0.0;  ///< m_perp' W m_perp
    double weighted_sum = 0.0; ///< m_perp' W r
  };
  TroposphereMismatchConfig cfg_;
  std::deque<FixTerm> window_;
};

}  // namespace deepnav::aiding
