#pragma once
// Single-epoch position, velocity and time from code pseudoranges and Doppler.
//
// Weighted least squares (Gauss-Newton) for ECEF position and clock bias with
// satellite positions at transmit time, Earth rotation during the flight (Sagnac),
// satellite clock with relativity and TGD, Klobuchar ionosphere and Saastamoinen
// troposphere; then velocity and clock drift from the Doppler-derived range rates.
// Weights: sigma^2 = a^2 + (b / sin el)^2 + c^2 10^(-(C/N0)/10) (elevation and C/N0
// terms; a = 0.5 m, b = 0.5 m, c chosen so 45 dB-Hz adds ~0.3 m). A residual
// chi-square test excludes the worst satellite and solves again (needs >= 6).
#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "signals/ephemeris.hpp"
#include "receiver/range_weight.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

struct PseudorangeObservation {
  int prn = 0;
  double pseudorange_m = 0.0;
  double doppler_hz = 0.0;   ///< carrier Doppler (positive when approaching)
  double cn0_dbhz = 45.0;
};

struct Dops {
  double gdop = 0, pdop = 0, hdop = 0, vdop = 0, tdop = 0;
};

struct PvtSolution {
  bool valid = false;
  std::string reason;               ///< why not valid
  GpsTime t{};                      ///< receiver clock time of the measurements
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  wgs84::Llh llh{};
  double clock_bias_m = 0.0;        ///< c * receiver clock bias
  double clock_drift_mps = 0.0;     ///< c * receiver clock drift
  Dops dops;
  std::vector<int> used_prns, excluded_prns;
  std::map<int, double> residuals_m;
  std::map<int, double> elevation_rad;
  std::map<int, double> azimuth_rad;
  int iterations = 0;
};

struct PvtConfig {
  double elevation_mask_rad = 5.0 * 3.14159265358979323846 / 180.0;
  bool ionosphere = true;
  bool troposphere = true;
  double chi2_probability = 1e-3;   ///< false-alarm probability of the residual test
  RangeErrorModel range_errors;     ///< pseudorange weights (the aided modes use the same)
};

class PvtSolver {
 public:
  explicit PvtSolver(PvtConfig config = {}) : cfg_(config) {}
  /// ephemerides by PRN; the last valid solution seeds the iteration.
  PvtSolution solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                    const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono);

 private:
  PvtSolution solve_once(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                         const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono) const;
  PvtConfig cfg_;
  Eigen::Vector4d seed_ = Eigen::Vector4d::Zero();
};

}  // namespace deepnav
