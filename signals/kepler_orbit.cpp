#include "signals/kepler_orbit.hpp"

#include <cmath>

namespace deepnav {

namespace {

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

}  // namespace

// IS-GPS-200 Table 20-IV (Galileo OS SIS ICD Table 64 alike), with the analytic time derivative
// of every step for the velocity.
KeplerSolution solve_kepler_orbit(const KeplerElements& el, double tk, const OrbitModelConstants& model) {
  const double a = el.sqrt_a * el.sqrt_a;
  const double n = std::sqrt(model.gm_m3ps2 / (a * a * a)) + el.delta_n_radps;
  const double mk = el.m0_rad + n * tk;
  const double ek = eccentric_anomaly_rad(mk, el.e);
  const double sin_e = std::sin(ek), cos_e = std::cos(ek);
  const double one_minus_ecos = 1.0 - el.e * cos_e;
  const double sqrt_1me2 = std::sqrt(1.0 - el.e * el.e);

  // True anomaly via atan2 of its sine and cosine (quadrant-safe form of Table 20-IV).
  const double vk = std::atan2(sqrt_1me2 * sin_e, cos_e - el.e);
  const double phi = vk + el.omega_rad;
  const double sin2p = std::sin(2.0 * phi), cos2p = std::cos(2.0 * phi);

  // Second harmonic perturbations.
  const double du = el.cus_rad * sin2p + el.cuc_rad * cos2p;
  const double dr = el.crs_m * sin2p + el.crc_m * cos2p;
  const double di = el.cis_rad * sin2p + el.cic_rad * cos2p;
  const double u = phi + du;
  const double r = a * one_minus_ecos + dr;
  const double inc = el.i0_rad + di + el.idot_radps * tk;

  const double xp = r * std::cos(u), yp = r * std::sin(u);
  // Corrected longitude of the ascending node, including Earth rotation since the start of
  // the week (toe) and during tk.
  const double omega_k =
      el.omega0_rad + (el.omega_dot_radps - model.earth_rate_radps) * tk - model.earth_rate_radps * el.toe_s;
  const double sin_o = std::sin(omega_k), cos_o = std::cos(omega_k);
  const double sin_i = std::sin(inc), cos_i = std::cos(inc);

  KeplerSolution s;
  s.r_ecef_m = {xp * cos_o - yp * cos_i * sin_o, xp * sin_o + yp * cos_i * cos_o, yp * sin_i};

  // Rates: dE/dt from Kepler's equation, dv/dt = dE/dt sqrt(1-e^2)/(1-e cos E).
  const double ek_dot = n / one_minus_ecos;
  const double phi_dot = ek_dot * sqrt_1me2 / one_minus_ecos;
  const double u_dot = phi_dot * (1.0 + 2.0 * (el.cus_rad * cos2p - el.cuc_rad * sin2p));
  const double r_dot = a * el.e * sin_e * ek_dot + 2.0 * phi_dot * (el.crs_m * cos2p - el.crc_m * sin2p);
  const double i_dot = el.idot_radps + 2.0 * phi_dot * (el.cis_rad * cos2p - el.cic_rad * sin2p);
  const double omega_k_dot = el.omega_dot_radps - model.earth_rate_radps;

  const double xp_dot = r_dot * std::cos(u) - yp * u_dot;
  const double yp_dot = r_dot * std::sin(u) + xp * u_dot;
  s.v_ecef_mps = {xp_dot * cos_o - yp_dot * cos_i * sin_o + yp * sin_i * sin_o * i_dot - s.r_ecef_m.y() * omega_k_dot,
                  xp_dot * sin_o + yp_dot * cos_i * cos_o - yp * sin_i * cos_o * i_dot + s.r_ecef_m.x() * omega_k_dot,
                  yp_dot * sin_i + yp * cos_i * i_dot};
  s.ecc_anomaly_rad = ek;
  s.ecc_anomaly_rate_radps = ek_dot;
  return s;
}

double seconds_from_reference(int week, double sow, int ref_week, double ref_sow) {
  const double full = GpsTime{week, sow}.seconds_since(GpsTime{ref_week, ref_sow});
  if (std::abs(full) <= kSecondsPerWeek / 2) return full;
  return seconds_of_week_difference(sow, ref_sow);
}

}  // namespace deepnav
