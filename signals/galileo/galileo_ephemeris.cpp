#include "signals/galileo/galileo_ephemeris.hpp"

#include <cmath>

#include "signals/galileo/galileo_constants.hpp"

namespace deepnav::galileo {
namespace {

constexpr OrbitModelConstants kGalileoOrbitModel{kGM_m3ps2, kEarthRate_radps};

/// The first index of each SISA range and the range's step and first value (ICD Table 89).
struct SisaRange {
  int first_index;
  double first_m;
  double step_m;
};
constexpr SisaRange kSisaRanges[] = {{0, 0.0, 0.01}, {50, 0.5, 0.02}, {75, 1.0, 0.04}, {100, 2.0, 0.16}};
constexpr int kSisaLastIndex = 125;
constexpr int kSisaNapa = 255;

}  // namespace

SatelliteState satellite_state(const GalileoEphemeris& eph, const GstTime& t) {
  const double tk = seconds_from_reference(t.week, t.tow_s, eph.week, eph.orbit.toe_s);
  const KeplerSolution orbit = solve_kepler_orbit(eph.orbit, tk, kGalileoOrbitModel);
  const double dt_clock = seconds_from_reference(t.week, t.tow_s, eph.week, eph.toc_s);
  const double sin_e = std::sin(orbit.ecc_anomaly_rad);
  const double cos_e = std::cos(orbit.ecc_anomaly_rad);

  SatelliteState st;
  st.r_ecef_m = orbit.r_ecef_m;
  st.v_ecef_mps = orbit.v_ecef_mps;
  st.relativistic_s = kRelativisticF * eph.orbit.e * eph.orbit.sqrt_a * sin_e;
  st.clock_bias_s = eph.af0_s + eph.af1_sps * dt_clock + eph.af2_sps2 * dt_clock * dt_clock + st.relativistic_s;
  st.clock_drift_sps = eph.af1_sps + 2.0 * eph.af2_sps2 * dt_clock +
                       kRelativisticF * eph.orbit.e * eph.orbit.sqrt_a * cos_e * orbit.ecc_anomaly_rate_radps;
  return st;
}

double e1_clock_correction_s(const GalileoEphemeris& eph, const GstTime& t) {
  return satellite_state(eph, t).clock_bias_s - (eph.clock_for_e1e5a() ? eph.bgd_e1e5a_s : eph.bgd_e1e5b_s);
}

std::optional<double> sisa_metres(int index) {
  if (index < 0 || index > kSisaLastIndex) return std::nullopt;
  const SisaRange* range = &kSisaRanges[0];
  for (const SisaRange& r : kSisaRanges) {
    if (index >= r.first_index) range = &r;
  }
  return range->first_m + range->step_m * (index - range->first_index);
}

int sisa_index_from_metres(double metres) {
  if (!(metres >= 0.0)) return kSisaNapa;
  for (int index = 0; index <= kSisaLastIndex; ++index) {
    // Half a centimetre of slack: files print the metres rounded.
    if (*sisa_metres(index) >= metres - 0.005) return index;
  }
  return kSisaNapa;
}

}  // namespace deepnav::galileo
