#pragma once
// Single-epoch position, velocity and time from code pseudoranges and Doppler.
//
// Weighted least squares (Gauss-Newton) for ECEF position and clock bias with
// satellite positions at transmit time, Earth rotation during the flight (Sagnac),
// satellite clock with relativity and TGD, and the atmosphere models chosen in
// AtmosphereModels (Klobuchar ionosphere and Saastamoinen troposphere by default); then
// velocity and clock drift from the Doppler-derived range rates.
// Weights: sigma^2 = a^2 + (b / sin el)^2 + c^2 10^(-(C/N0)/10) (elevation and C/N0
// terms; a = 0.5 m, b = 0.5 m, c chosen so 45 dB-Hz adds ~0.3 m; receiver/pvt/range_weight.hpp,
// the same weights as the aided modes).
//
// RAIM fault detection and exclusion (receiver/pvt/raim.hpp), per epoch: with 5 or more
// satellites the weighted residual chi-square test runs at the configured false-alarm
// probability; on a detection the satellite with the largest standardised residual is
// excluded and the fix solved and tested again, up to `raim_max_exclusions` times and
// only while 5 or more satellites remain (so the test still runs on what is left). A fix
// that still fails the test is flagged (raim = failed) and not published as valid: an
// undetected bias of tens of metres is worse than one missing epoch.
#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "receiver/pvt/atmosphere_models.hpp"
#include "receiver/pvt/range_weight.hpp"
#include "signals/ephemeris.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

struct PseudorangeObservation {
  int prn = 0;
  double pseudorange_m = 0.0;
  double doppler_hz = 0.0;  ///< carrier Doppler (positive when approaching)
  double cn0_dbhz = 45.0;
};

struct Dops {
  double gdop = 0, pdop = 0, hdop = 0, vdop = 0, tdop = 0;
};

/// Outcome of the RAIM residual test of a fix.
enum class RaimStatus {
  unavailable,  ///< fewer than 5 satellites: no redundancy to test (or no fix)
  passed,       ///< no fault detected
  excluded,     ///< faults detected and excluded (excluded_prns); the rest passed
  failed,       ///< a fault detected that could not be excluded: the fix is not valid
};
std::string to_string(RaimStatus status);

struct PvtSolution {
  bool valid = false;
  std::string reason;  ///< why not valid
  GpsTime t{};         ///< receiver clock time of the measurements
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  wgs84::Llh llh{};
  double clock_bias_m = 0.0;     ///< c * receiver clock bias
  double clock_drift_mps = 0.0;  ///< c * receiver clock drift
  Dops dops;
  std::vector<int> used_prns, excluded_prns;  ///< excluded: by RAIM, in the order found
  RaimStatus raim = RaimStatus::unavailable;
  double raim_statistic = 0.0;  ///< weighted residual sum of squares of the fix (last test)
  double raim_threshold = 0.0;  ///< its chi-square bound (0: not tested)
  std::map<int, double> residuals_m;
  std::map<int, double> elevation_rad;
  std::map<int, double> azimuth_rad;
  std::map<int, double> ionosphere_m;  ///< the ionosphere model's delay applied to each pseudorange
  int iterations = 0;
};

struct PvtConfig {
  double elevation_mask_rad = 5.0 * 3.14159265358979323846 / 180.0;
  /// RAIM: probability that the residual test flags a fault-free epoch (per test).
  double raim_false_alarm_probability = 1e-3;
  /// RAIM: satellites excluded at most per epoch before the fix is declared failed.
  int raim_max_exclusions = 2;
  RangeErrorModel range_errors;  ///< pseudorange weights (the aided modes use the same)
  /// A fix outside these heights (WGS-84, m) is no fix: with four satellites nothing else
  /// can catch a pseudorange off by a millisecond of transmit time, which puts a fix
  /// hundreds of kilometres up (seen in the suburban world at 612 km).
  double min_height_m = -1000.0;
  double max_height_m = 100000.0;
};

class PvtSolver {
 public:
  /// `atmosphere`: the receiver's choice of models (ReceiverConfig::atmosphere).
  explicit PvtSolver(PvtConfig config = {}, AtmosphereModels atmosphere = {}) : cfg_(config), atmosphere_(atmosphere) {}
  /// ephemerides by PRN; the last valid solution seeds the iteration. `iono` is used
  /// only with the Klobuchar model (and only when valid).
  PvtSolution solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                    const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono);

 private:
  PvtConfig cfg_;
  AtmosphereModels atmosphere_;
  Eigen::Vector4d seed_ = Eigen::Vector4d::Zero();
};

}  // namespace deepnav
