#pragma once
// A first position from carrier Dopplers alone, for a coarse-time fix without a position
// hint: the Doppler of each satellite depends on where the receiver is (the satellite's
// velocity projected on the line of sight), so the Dopplers at a roughly known time fix a
// static receiver's position and clock drift (four unknowns):
//   -lambda f_k = u_k . v_k / (1 + k_k) + d - c dts'_k          (receiver/pvt/range_model.hpp)
// with u_k the line of sight, v_k the satellite velocity, d the receiver clock drift (m/s).
// Its row is [-(v_k - (u_k . v_k) u_k)' / rho_k, 1] / -lambda: a Doppler moves by about
// 1 Hz per km of position, so Dopplers good to tens of Hz give tens of km, well inside
// the 150 km the whole milliseconds of the code phases tolerate.
//
// What it assumes: a static receiver (each m/s of velocity moves the fix by ~5 km along
// it) and a time good to about a minute (the Dopplers drift by up to ~1 Hz/s). The
// problem is not linear over the Earth: Gauss-Newton starts from every point of a coarse
// grid over where all the satellites are above the horizon (surface_grid.hpp) and the
// best-fitting converged solution is kept; its weighted residuals are tested against the
// chi-square bound (n - 4 degrees of freedom) with the configured Doppler sigma.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "signals/ephemeris.hpp"

namespace deepnav {

struct DopplerSatellite {
  int prn = 0;
  const Ephemeris* ephemeris = nullptr;
  double doppler_hz = 0.0;  ///< carrier Doppler, positive when approaching
};

struct DopplerPositionConfig {
  double doppler_sigma_hz = 25.0;         ///< 1 sigma of a measured Doppler (weights and test)
  double false_alarm_probability = 1e-3;  ///< of the residual test
  int max_iterations = 20;
  double start_spacing_m = 1500e3;                                   ///< of the grid of starting points
  double min_elevation_rad = -5.0 * 3.14159265358979323846 / 180.0;  ///< visibility of the starts
};

struct DopplerPosition {
  bool valid = false;
  std::string reason;  ///< why not valid
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  double clock_drift_mps = 0.0;                             ///< c * receiver clock drift
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();  ///< of the position, with the configured sigma
  double statistic = 0.0, threshold = 0.0;                  ///< residual test (0 threshold: not run)
  int dof = 0;
  double residual_rms_hz = 0.0;
  std::map<int, double> residuals_hz;
  int starts = 0;  ///< starting points tried
};

/// Needs at least 5 satellites (4 unknowns and one to test); `t` is the approximate GPS
/// time of the measurements.
DopplerPosition solve_doppler_position(const std::vector<DopplerSatellite>& satellites, const GpsTime& t,
                                       const DopplerPositionConfig& config = {});

}  // namespace deepnav
