#include "signals/ephemeris.hpp"

#include <cmath>

#include "signals/gps_constants.hpp"

namespace deepnav {

namespace {

/// Time from the ephemeris reference (week, ref_sow) to t. With a known week the full
/// difference is used, so data sets whose toe lies in the previous or next week work;
/// when the weeks are unknown or inconsistent (|dt| beyond half a week), IS-GPS-200's
/// end/start-of-week fold of the seconds-of-week difference is applied instead.
double seconds_from_reference(const GpsTime& t, int ref_week, double ref_sow) {
  const double full = t.seconds_since(GpsTime{ref_week, ref_sow});
  if (std::abs(full) <= kSecondsPerWeek / 2) return full;
  return seconds_of_week_difference(t.sow, ref_sow);
}

/// Eccentric anomaly from Kepler's equation M = E - e sin E by Newton iteration.
double eccentric_anomaly_rad(double mean_anomaly_rad, double e) {
  double ecc = mean_anomaly_rad;
  for (int i = 0; i < 30; ++i) {
    const double step = (ecc - e * std::sin(ecc) - mean_anomaly_rad) / (1.0 - e * std::cos(ecc));
    ecc -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return ecc;
}

struct OrbitSolution {
  Eigen::Vector3d r_ecef_m;
  Eigen::Vector3d v_ecef_mps;
  double ecc_anomaly_rad;
  double ecc_anomaly_rate_radps;
};

/// IS-GPS-200 Table 20-IV, with the analytic time derivative of every step for the velocity.
OrbitSolution solve_orbit(const Ephemeris& eph, double tk) {
  const double a = eph.sqrt_a * eph.sqrt_a;
  const double n = std::sqrt(gps::kGM_m3ps2 / (a * a * a)) + eph.delta_n_radps;
  const double mk = eph.m0_rad + n * tk;
  const double ek = eccentric_anomaly_rad(mk, eph.e);
  const double sin_e = std::sin(ek), cos_e = std::cos(ek);
  const double one_minus_ecos = 1.0 - eph.e * cos_e;
  const double sqrt_1me2 = std::sqrt(1.0 - eph.e * eph.e);

  // True anomaly via atan2 of its sine and cosine (quadrant-safe form of Table 20-IV).
  const double vk = std::atan2(sqrt_1me2 * sin_e, cos_e - eph.e);
  const double phi = vk + eph.omega_rad;
  const double sin2p = std::sin(2.0 * phi), cos2p = std::cos(2.0 * phi);

  // Second harmonic perturbations.
  const double du = eph.cus_rad * sin2p + eph.cuc_rad * cos2p;
  const double dr = eph.crs_m * sin2p + eph.crc_m * cos2p;
  const double di = eph.cis_rad * sin2p + eph.cic_rad * cos2p;
  const double u = phi + du;
  const double r = a * one_minus_ecos + dr;
  const double inc = eph.i0_rad + di + eph.idot_radps * tk;

  const double xp = r * std::cos(u), yp = r * std::sin(u);
  // Corrected longitude of the ascending node, including Earth rotation since the start of
  // the week (toe) and during tk.
  const double omega_k =
      eph.omega0_rad + (eph.omega_dot_radps - gps::kEarthRate_radps) * tk - gps::kEarthRate_radps * eph.toe_s;
  const double sin_o = std::sin(omega_k), cos_o = std::cos(omega_k);
  const double sin_i = std::sin(inc), cos_i = std::cos(inc);

  OrbitSolution s;
  s.r_ecef_m = {xp * cos_o - yp * cos_i * sin_o, xp * sin_o + yp * cos_i * cos_o, yp * sin_i};

  // Rates: dE/dt from Kepler's equation, dv/dt = dE/dt sqrt(1-e^2)/(1-e cos E).
  const double ek_dot = n / one_minus_ecos;
  const double phi_dot = ek_dot * sqrt_1me2 / one_minus_ecos;
  const double u_dot = phi_dot * (1.0 + 2.0 * (eph.cus_rad * cos2p - eph.cuc_rad * sin2p));
  const double r_dot = a * eph.e * sin_e * ek_dot + 2.0 * phi_dot * (eph.crs_m * cos2p - eph.crc_m * sin2p);
  const double i_dot = eph.idot_radps + 2.0 * phi_dot * (eph.cis_rad * cos2p - eph.cic_rad * sin2p);
  const double omega_k_dot = eph.omega_dot_radps - gps::kEarthRate_radps;

  const double xp_dot = r_dot * std::cos(u) - yp * u_dot;
  const double yp_dot = r_dot * std::sin(u) + xp * u_dot;
  s.v_ecef_mps = {xp_dot * cos_o - yp_dot * cos_i * sin_o + yp * sin_i * sin_o * i_dot - s.r_ecef_m.y() * omega_k_dot,
                  xp_dot * sin_o + yp_dot * cos_i * cos_o - yp * sin_i * cos_o * i_dot + s.r_ecef_m.x() * omega_k_dot,
                  yp_dot * sin_i + yp * cos_i * i_dot};
  s.ecc_anomaly_rad = ek;
  s.ecc_anomaly_rate_radps = ek_dot;
  return s;
}

}  // namespace

SatelliteState satellite_state(const Ephemeris& eph, const GpsTime& t) {
  const double tk = seconds_from_reference(t, eph.week, eph.toe_s);
  const OrbitSolution orbit = solve_orbit(eph, tk);

  // toc is in the week of toe except right at a week crossover, which the fold handles.
  const double dt_clock = seconds_from_reference(t, eph.week, eph.toc_s);
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
