#pragma once
// Coarse-time navigation: a position from the code phases of one snapshot (transmit time
// modulo 1 ms per satellite), the broadcast ephemerides and an approximate time, before
// (or without) any time of week decoded from the navigation message. The standard A-GPS
// method (F. van Diggelen, "A-GPS: Assisted GPS, GNSS and SBAS", Artech House 2009, ch. 4):
// the whole milliseconds of each pseudorange from a predicted range, and the time error as
// a fifth unknown (receiver/pvt/coarse_time_fit.hpp).
//
// With a position hint: the whole milliseconds come from the hint, and the fix is
// checked (receiver/pvt/coarse_time_integrity.hpp: residual test, wrong whole
// milliseconds repaired or excluded). Tolerated: a hint within ~100 km and a time within
// ~1-2 minutes (the sum of both effects on the predicted ranges must stay below 150 km,
// see coarse_time_fit.hpp).
//
// Without a position hint (receiver/pvt/coarse_time_search.hpp): a first position from
// the Dopplers, when 5 or more are measured, and a grid of candidates around it; else a
// grid over every place from which all the satellites are above the horizon. Each
// candidate's whole milliseconds are fitted; the fix is accepted only when exactly one
// place passes.
//
// Never a wrong fix from a wrong hint: a fix is published only when its residuals pass
// the test, it lies within the tolerances of the hints (position_hint_tolerance_m,
// time_hint_tolerance_s), at a plausible height, and every satellite is above the
// horizon there. Otherwise it is refused with a reason that names the suspect hint and by
// how much it is off, found by solving again without it: without the position hint (the
// fix that then comes out is that far from it) or, at the hinted position, at other times
// (the time at which the code phases fit).
#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "receiver/pvt/atmosphere_models.hpp"
#include "receiver/pvt/coarse_time_config.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "receiver/pvt/snapshot_measurement.hpp"
#include "signals/ephemeris.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

struct CoarseTimeHints {
  GpsTime time{};  ///< approximate time of the receive sample (the receiver clock's reading of it)
  std::optional<Eigen::Vector3d> position_ecef_m;
};

/// Where the fix's whole milliseconds came from.
enum class CoarseTimeStart { position_hint, doppler, grid };
std::string to_string(CoarseTimeStart start);

/// Which hint a refusal blames.
enum class SuspectHint {
  none,       ///< a fix, or a refusal for another reason (too few satellites)
  position,   ///< the code phases fit elsewhere at the hinted time
  time,       ///< the code phases fit the hinted position at another time
  unknown,    ///< the code phases fit neither: both hints, or the measurements
  ambiguous,  ///< several places fit (no position hint): give one
};
std::string to_string(SuspectHint suspect);

struct CoarseTimeQuality {
  double residual_rms_m = 0.0;
  double chi_square = 0.0;            ///< weighted sum of squared residuals
  double chi_square_threshold = 0.0;  ///< its bound at the false-alarm probability (0: not tested)
  int degrees_of_freedom = 0;         ///< satellites used - 5
  bool passed = false;
  int iterations = 0;  ///< of the final fit
  int candidates = 0;  ///< whole-millisecond sets tried
};

struct CoarseTimeFix {
  bool valid = false;
  std::string reason;  ///< why refused (empty for a fix)
  SuspectHint suspect = SuspectHint::none;
  /// How far the suspect hint is off, when the diagnosis found the fix without it.
  std::optional<double> position_hint_error_m;
  std::optional<double> time_hint_error_s;

  CoarseTimeStart start = CoarseTimeStart::position_hint;
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  wgs84::Llh llh{};
  /// c (receiver clock - GPS time) at the sample, modulo c * 1 ms: the pseudoranges'
  /// common offset (the whole milliseconds of the clock are in the time correction).
  double clock_bias_m = 0.0;
  std::optional<double> clock_drift_mps;  ///< from the Doppler position, when one was made
  double coarse_time_correction_s = 0.0;  ///< true receive time minus the time hint
  GpsTime receive_time{};                 ///< GPS time of the sample: hint + correction
  Dops dops;                              ///< of position and clock bias
  double coarse_time_dop_s_per_m = 0.0;   ///< sigma of the time correction per metre of range sigma
  std::vector<int> used_prns;
  std::vector<int> excluded_prns;       ///< by the residual test
  std::vector<int> without_ephemeris;   ///< measured, but no ephemeris given
  std::map<int, int> repaired_ms;       ///< PRN -> whole milliseconds changed by the residual test
  std::map<int, double> pseudorange_m;  ///< the full pseudoranges fitted
  std::map<int, double> residuals_m;
  std::map<int, double> elevation_rad;
  CoarseTimeQuality quality;
};

class CoarseTimeSolver {
 public:
  explicit CoarseTimeSolver(CoarseTimeConfig config = {}, AtmosphereModels atmosphere = {})
      : cfg_(config), atmosphere_(atmosphere) {}

  /// `ephemerides` by PRN (those valid at the hinted time); `iono` is used with the
  /// Klobuchar model when valid. Throws std::invalid_argument for malformed measurements
  /// (snapshot_measurement.hpp) or a position hint that is not a finite position within
  /// 100 km of the ellipsoid's surface.
  CoarseTimeFix solve(const std::vector<SnapshotMeasurement>& measurements, const std::map<int, Ephemeris>& ephemerides,
                      const IonoParameters& iono, const CoarseTimeHints& hints) const;

 private:
  CoarseTimeConfig cfg_;
  AtmosphereModels atmosphere_;
};

}  // namespace deepnav
