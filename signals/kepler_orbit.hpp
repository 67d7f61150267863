#pragma once
// The broadcast Keplerian orbit model that GPS (IS-GPS-200 Table 20-IV) and Galileo (OS SIS
// ICD Table 64) share: sixteen quasi-Keplerian elements with harmonic corrections, evaluated
// with each system's own GM and Earth rotation rate.
#include <Eigen/Core>

#include "ins/gps_time.hpp"

namespace deepnav {

/// The orbital elements of one broadcast data set. Angles in radians.
struct KeplerElements {
  double toe_s = 0.0;   ///< reference time, seconds of week
  double sqrt_a = 0.0;  ///< sqrt(m)
  double e = 0.0;
  double m0_rad = 0.0, delta_n_radps = 0.0;
  double omega0_rad = 0.0, omega_dot_radps = 0.0;
  double i0_rad = 0.0, idot_radps = 0.0;
  double omega_rad = 0.0;  ///< argument of perigee
  double cuc_rad = 0.0, cus_rad = 0.0, crc_m = 0.0, crs_m = 0.0, cic_rad = 0.0, cis_rad = 0.0;
};

/// What distinguishes one system's evaluation of the model from another's.
struct OrbitModelConstants {
  double gm_m3ps2;
  double earth_rate_radps;
};

struct KeplerSolution {
  Eigen::Vector3d r_ecef_m;    ///< in the ECEF frame at the evaluation time
  Eigen::Vector3d v_ecef_mps;  ///< analytic time derivative of every step of the model
  double ecc_anomaly_rad;
  double ecc_anomaly_rate_radps;
};

/// Position and velocity tk seconds after toe.
KeplerSolution solve_kepler_orbit(const KeplerElements& el, double tk, const OrbitModelConstants& model);

/// Time from a reference (week, seconds of week) to (week, sow). With weeks known the full
/// difference is used, so data sets whose reference lies in the previous or next week work;
/// when the weeks are unknown or inconsistent (|dt| beyond half a week) the end/start-of-week
/// fold of the seconds-of-week difference applies instead (IS-GPS-200 20.3.3.4.3, and the
/// same for GST).
double seconds_from_reference(int week, double sow, int ref_week, double ref_sow);

}  // namespace deepnav
