#include "signals/ephemeris.hpp"

#include <cmath>

#include "signals/gps_constants.hpp"
#include "signals/kepler_orbit.hpp"

namespace deepnav {

namespace {

constexpr OrbitModelConstants kGpsOrbitModel{gps::kGM_m3ps2, gps::kEarthRate_radps};

KeplerElements kepler_elements(const Ephemeris& eph) {
  KeplerElements el;
  el.toe_s = eph.toe_s;
  el.sqrt_a = eph.sqrt_a;
  el.e = eph.e;
  el.m0_rad = eph.m0_rad;
  el.delta_n_radps = eph.delta_n_radps;
  el.omega0_rad = eph.omega0_rad;
  el.omega_dot_radps = eph.omega_dot_radps;
  el.i0_rad = eph.i0_rad;
  el.idot_radps = eph.idot_radps;
  el.omega_rad = eph.omega_rad;
  el.cuc_rad = eph.cuc_rad;
  el.cus_rad = eph.cus_rad;
  el.crc_m = eph.crc_m;
  el.crs_m = eph.crs_m;
  el.cic_rad = eph.cic_rad;
  el.cis_rad = eph.cis_rad;
  return el;
}

}  // namespace

SatelliteState satellite_state(const Ephemeris& eph, const GpsTime& t) {
  const double tk = seconds_from_reference(t.week, t.sow, eph.week, eph.toe_s);
  const KeplerSolution orbit = solve_kepler_orbit(kepler_elements(eph), tk, kGpsOrbitModel);

  // toc is in the week of toe except right at a week crossover, which the fold handles.
  const double dt_clock = seconds_from_reference(t.week, t.sow, eph.week, eph.toc_s);
  const double sin_e = std::sin(orbit.ecc_anomaly_rad);
  const double cos_e = std::cos(orbit.ecc_anomaly_rad);

  SatelliteState st;
  st.r_ecef_m = orbit.r_ecef_m;
  st.v_ecef_mps = orbit.v_ecef_mps;
  st.relativistic_s = gps::kRelativisticF * eph.e * eph.sqrt_a * sin_e;
  st.clock_bias_s = eph.af0_s + eph.af1_sps * dt_clock + eph.af2_sps2 * dt_clock * dt_clock + st.relativistic_s;
  st.clock_drift_sps = eph.af1_sps + 2.0 * eph.af2_sps2 * dt_clock +
                       gps::kRelativisticF * eph.e * eph.sqrt_a * cos_e * orbit.ecc_anomaly_rate_radps;
  return st;
}

double l1_clock_correction_s(const Ephemeris& eph, const GpsTime& t) {
  return satellite_state(eph, t).clock_bias_s - eph.tgd_s;
}

Eigen::Vector3d earth_rotation_corrected(const Eigen::Vector3d& r_ecef_at_tx, double tau_s) {
  // The ECEF frame turns by omega_e tau during the flight; in the later frame the
  // satellite appears rotated by -omega_e tau about z.
  const double angle = gps::kEarthRate_radps * tau_s;
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * r_ecef_at_tx.x() + s * r_ecef_at_tx.y(), -s * r_ecef_at_tx.x() + c * r_ecef_at_tx.y(), r_ecef_at_tx.z()};
}

double fit_interval_s(const Ephemeris& eph) {
  if (eph.fit_interval_flag == 0) return 4.0 * 3600.0;
  // IS-GPS-200 Tables 20-XI/20-XII: the IODC tells the extended fit interval.
  const int iodc = eph.iodc;
  double hours = 6.0;
  if (iodc >= 240 && iodc <= 247) hours = 8.0;
  else if ((iodc >= 248 && iodc <= 255) || iodc == 496) hours = 14.0;
  else if (iodc >= 497 && iodc <= 503) hours = 26.0;
  else if (iodc >= 504 && iodc <= 510) hours = 50.0;
  else if (iodc == 511 || (iodc >= 752 && iodc <= 756)) hours = 74.0;
  else if (iodc == 757) hours = 98.0;
  return hours * 3600.0;
}

}  // namespace deepnav
