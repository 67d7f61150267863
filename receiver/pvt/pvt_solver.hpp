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
//
// GPS and Galileo together: one receiver clock per system. With satellites of both
// systems the state is position, the receiver clock against GPS time and the offset of
// the Galileo measurements' clock from it (x, y, z, c dt_G, c dt_EG: a Galileo row is
// range + c dt_G + c dt_EG); with one system only it is the four of a GPS fix, the clock
// being that system's (Galileo-only: against Galileo System Time, so four Galileo
// satellites fix). The broadcast GGTO (GST - GPST) is not applied: the offset state
// absorbs it together with the receiver's own inter-system bias (its E1 and L1 C/A paths
// differ by nanoseconds too, and nothing broadcast tells that part), so applying the GGTO
// would move only the split between the two and make the fix depend on a parameter the
// receiver may not have decoded yet. The offset costs one satellite of redundancy: RAIM's
// degrees of freedom are n - 5 in a mixed fix. Galileo ranges weigh as GPS ones (the same
// elevation and C/N0 model; like URA for GPS, SISA does not enter the weight) and Galileo
// E1 shares L1's frequency, so the Klobuchar ionosphere of the GPS message applies to it.
// The velocity has one clock drift (both systems' measurements count the receiver's one
// oscillator); the DOPs are of position and the first clock (GDOP: position and that
// clock, as RTKLIB reports it).
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
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/iono_utc.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

struct PseudorangeObservation {
  int prn = 0;
  double pseudorange_m = 0.0;
  double doppler_hz = 0.0;  ///< carrier Doppler (positive when approaching)
  double cn0_dbhz = 45.0;
  GnssSystem system = GnssSystem::gps;  ///< whose satellite `prn` numbers

  SatelliteId satellite() const { return {system, prn}; }
};

struct Dops {
  double gdop = 0, pdop = 0, hdop = 0, vdop = 0, tdop = 0;
};

/// Outcome of the RAIM residual test of a fix.
enum class RaimStatus {
  unavailable,  ///< fewer than 5 satellites: no redundancy to test (or no fix)
  passed,       ///< no fault detected
  excluded,     ///< faults detected and excluded (excluded_satellites); the rest passed
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
  double clock_bias_m = 0.0;                  ///< c * receiver clock bias against clock_system's time
  GnssSystem clock_system = GnssSystem::gps;  ///< GPS whenever a GPS satellite is used
  /// c * (clock of the Galileo measurements - GPS clock) in a fix with both systems: GGTO
  /// plus the receiver's inter-system bias; nullopt with one system.
  std::optional<double> system_offset_m;
  double clock_drift_mps = 0.0;  ///< c * receiver clock drift
  Dops dops;
  /// excluded: by RAIM, in the order found.
  std::vector<SatelliteId> used_satellites, excluded_satellites;
  RaimStatus raim = RaimStatus::unavailable;
  double raim_statistic = 0.0;  ///< weighted residual sum of squares of the fix (last test)
  double raim_threshold = 0.0;  ///< its chi-square bound (0: not tested)
  std::map<SatelliteId, double> residuals_m;
  std::map<SatelliteId, double> elevation_rad;
  std::map<SatelliteId, double> azimuth_rad;
  std::map<SatelliteId, double> ionosphere_m;  ///< the ionosphere model's delay applied to each pseudorange

  /// How many satellites of `system` the fix uses.
  int used_count(GnssSystem system) const;
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
  /// only with the Klobuchar model (and only when valid). GPS observations only.
  PvtSolution solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                    const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono);
  /// GPS and Galileo observations, each satellite's state from its system's ephemerides
  /// (Galileo by SVID); an observation without one is left out.
  PvtSolution solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                    const std::map<int, Ephemeris>& ephemerides,
                    const std::map<int, galileo::GalileoEphemeris>& galileo_ephemerides, const IonoParameters& iono);

 private:
  PvtConfig cfg_;
  AtmosphereModels atmosphere_;
  Eigen::Vector4d seed_ = Eigen::Vector4d::Zero();
  double seed_offset_m_ = 0.0;  ///< the inter-system offset of the last mixed fix
};

}  // namespace deepnav
