#pragma once
// Watches the pseudorange residuals for an atmosphere model that does not match the
// signal. An error e of a delay model adds e * s_i to satellite i's residual, s_i the
// error's signature: for the troposphere the receiver's mapping function m(el) (e: the
// zenith delay error, m), for the ionosphere the model's own delay for that look (e: the
// error of the model's scale, dimensionless; -1 when the signal has no ionosphere). Per
// epoch e is fitted by weighted least squares with the position and clock errors as
// nuisances (only the part of s they cannot take tells), and over a window of epochs the
// fits are combined. The residuals are the scalar PVT's
// (post-fit) in scalar, loose and tight mode, and the ultra-tight discriminator
// measurements' against the filter in ultra-tight mode (whose steered channels' own
// pseudoranges only echo the filter's prediction).
//
// A verdict needs the fixes to agree (DelayMismatchConfig::min_consistency): a model error
// is the same at every fix, while the part of multipath errors that looks like one is not.
//
// Troposphere: a standard atmosphere is wrong by centimetres to a decimetre or two at the zenith; a
// model delay 1.5 m larger than the signal's means the signal has none (IF from a
// generator without troposphere: the fit reads -1.9 to -2.3 m). The test is one-sided:
// reflected and non-line-of-sight signals add delay, most at low elevation, and read
// mostly as the opposite sign (suburban world: +1.1 to +1.2 m, once -1.06 m).
// The aided filter then takes its zenith troposphere state (aided_navigator.hpp): without
// it, the tight and ultra-tight filters turn the model's elevation-dependent error, and
// its rate in every Doppler and carrier row, into metres of height (measured on the
// aircraft circle without troposphere in the signal: ultra-tight 0.72 m horizontal, 6.8 m
// 3-D, against 0.12 m and 1.0 m with the state).
// Ionosphere: Klobuchar leaves about half of the delay (its scale is wrong by tens of per
// cent); a fit near -1 means the signal has none of it (IF from a generator without
// ionosphere), and the filter takes its ionosphere scale state.
#include <Eigen/Core>
#include <deque>
#include <map>
#include <optional>
#include <vector>

#include "receiver/pvt/pvt_solver.hpp"
#include "receiver/pvt/range_weight.hpp"

namespace deepnav::aiding {

/// Which model error the detector fits (see above).
enum class DelaySignature { troposphere_zenith, ionosphere_scale };

struct DelayMismatchConfig {
  DelaySignature signature = DelaySignature::troposphere_zenith;
  /// The model over the signal by this (troposphere: m at the zenith; ionosphere: a
  /// fraction of the model's delay): a mismatch.
  double threshold = 1.5;
  int window_fixes = 30;  ///< fixes combined
  int min_fixes = 20;     ///< before any verdict
  /// The fixes must agree on the error: the window's mean over the standard error of its
  /// per-fix fits (their own scatter, as if independent) beyond this. A missing delay reads
  /// the same at every fix (measured on the land and aircraft circles: 8.8 to 34); the
  /// common part of multipath and non-line-of-sight errors in a suburban street swings from
  /// fix to fix, and a 30-fix window of it reaches the threshold now and then at about 3
  /// (the worst window of a 90 s suburban land circle; the ionosphere detector fired on the
  /// first suburban runs tried before this test). Multipath is correlated over seconds, so
  /// the figure is optimistic: hence 6.
  double min_consistency = 6.0;
  /// Another model's error fitted beside this one, eliminated like the position and clock
  /// (needs one satellite more). Once the troposphere state is on, the ionosphere watch asks
  /// what is left that only the ionosphere's signature explains: a signal lacking both
  /// delays reads as a troposphere error first (the zenith fit takes the part of the
  /// missing ionosphere that looks like troposphere: -2.6 to -2.8 m against -1.8 to -2.2 m
  /// with the troposphere alone missing), and the single-signature ionosphere fit of the
  /// rest is too small to tell; eliminating the troposphere's signature gives the scale
  /// error unbiased, at the cost of a noisier fit.
  std::optional<DelaySignature> also_fitted = std::nullopt;
  /// The lowest error a signal can show (troposphere: a signal without any reads the model's
  /// zenith delay, about -2.3 m at sea level, -2.6 to -2.8 m with the ionosphere missing too;
  /// ionosphere: -1, no delay at all, read as -0.8 to -1.2). A window fitting below it is
  /// no model the signal could have but something else, wild fixes or multipath, and gets no
  /// verdict: on a 7-satellite night sky in Helsinki the ionosphere watch read scales of
  /// -2 to -4 (a negative delay) and the troposphere watch -2240 m and -197 km, and the
  /// filter took those states and left the truth by kilometres. A single fix fitting beyond
  /// five times it either way is left out of the window.
  double plausible_floor = -4.0;
};

/// One satellite's pseudorange residual (measured minus predicted) at an epoch.
struct RangeResidual {
  Eigen::Vector3d los = Eigen::Vector3d::UnitZ();  ///< unit line of sight, any frame (the same for an epoch)
  double elevation_rad = 0.0;
  double cn0_dbhz = 45.0;
  double residual_m = 0.0;
  double ionosphere_model_m = 0.0;  ///< the receiver's ionosphere model's delay for this look
};

/// A valid fix's residuals (look angles and ionosphere model from the fix; `cn0_dbhz` per PRN).
std::vector<RangeResidual> fix_residuals(const PvtSolution& fix, const std::map<int, double>& cn0_dbhz);

/// What a watch for a model mismatch found: when (nullopt: not found), the model error
/// fitted (as found, or the latest fit while none is), and when the filter took the
/// model's state on it (its first tight or ultra-tight epoch from then), starting it from
/// the fit with this much room (1-sigma, m) for the height and clock to move back; and
/// the state's estimate at the end (nullopt while it is off).
struct DelayMismatchReport {
  std::optional<double> found_at_s;
  double fitted_error = 0.0;
  std::optional<double> state_from_s;
  std::optional<double> height_room_m;
  std::optional<double> state_estimate;
};

class DelayMismatchDetector {
 public:
  explicit DelayMismatchDetector(DelayMismatchConfig config = {}) : cfg_(config) {}
  /// One epoch's residuals, weighted by `weights` (the PVT's model).
  void add(const std::vector<RangeResidual>& epoch, const RangeErrorModel& weights);
  /// The combined estimate of the model's error over the window (troposphere: zenith
  /// metres; ionosphere: scale; 0 before min_fixes).
  double fitted_error() const;
  /// The window's mean fit over the standard error of its per-fix fits (0 before
  /// min_fixes; infinite when every fix reads exactly the same).
  double consistency() const;
  /// fitted_error() below -threshold but not below plausible_floor, with a consistency
  /// beyond min_consistency.
  bool mismatch() const;

 private:
  struct FixTerm {
    double information = 0.0;   ///< m_perp' W m_perp
    double weighted_sum = 0.0;  ///< m_perp' W r
  };
  DelayMismatchConfig cfg_;
  std::deque<FixTerm> window_;
};

}  // namespace deepnav::aiding
