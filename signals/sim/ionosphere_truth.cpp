#include "signals/sim/ionosphere_truth.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "signals/gps_constants.hpp"
#include "signals/sim/error_seed.hpp"

namespace deepnav {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kEarthRadius_m = 6371e3;  // mean radius: the thin shell is a sphere
constexpr double kTecu = 1e16;             // electrons per m^2

// North geomagnetic (dipole) pole, IGRF-13 at epoch 2020.0.
constexpr double kPoleLat_rad = 80.65 * kDeg;
constexpr double kPoleLon_rad = -72.68 * kDeg;

/// Diurnal shape of the vertical TEC in local solar time (hours): 0 at 05 h (pre-dawn
/// minimum), 1 at 14 h, a 9 h rise and a slower 15 h decay through the night, both
/// half cosines (smooth at the turning points). Klobuchar's cosine is symmetric about
/// 14 h and flat at night, so its residual changes with the time of day.
double diurnal_shape(double local_time_h) {
  if (local_time_h >= 5.0 && local_time_h <= 14.0) return 0.5 * (1.0 - std::cos(kPi * (local_time_h - 5.0) / 9.0));
  const double since_peak_h = local_time_h >= 14.0 ? local_time_h - 14.0 : local_time_h + 10.0;
  return 0.5 * (1.0 + std::cos(kPi * since_peak_h / 15.0));
}

/// Latitude profile: 1 on the crests of the equatorial anomaly (|geomagnetic latitude|
/// 15 deg), 0.89 on the magnetic equator, 0.75 at 40 deg, 0.55 at 60 deg, 0.5 at the poles.
/// Flatter than the real fall towards the poles, so that the residual after Klobuchar (whose
/// daytime amplitude varies little with latitude) stays about the same everywhere.
double latitude_profile(double geomagnetic_lat_rad) {
  const double x = (std::abs(geomagnetic_lat_rad) - 15.0 * kDeg) / (30.0 * kDeg);
  return 0.5 + 0.5 * std::exp(-x * x);
}

double geomagnetic_latitude_rad(double lat_rad, double lon_rad) {
  const double s = std::sin(lat_rad) * std::sin(kPoleLat_rad) +
                   std::cos(lat_rad) * std::cos(kPoleLat_rad) * std::cos(lon_rad - kPoleLon_rad);
  return std::asin(std::clamp(s, -1.0, 1.0));
}

double wrap_pi(double a) { return std::remainder(a, 2.0 * kPi); }

}  // namespace

double single_layer_mapping(double elevation_rad, double shell_height_m) {
  const double x = kEarthRadius_m * std::cos(std::max(elevation_rad, 0.0)) / (kEarthRadius_m + shell_height_m);
  return 1.0 / std::sqrt(1.0 - x * x);
}

double l1_delay_m_from_tecu(double slant_tecu) { return 40.3 * slant_tecu * kTecu / (gps::kL1_Hz * gps::kL1_Hz); }

IonosphereTruth::IonosphereTruth(const IonosphereTruthSpec& spec, std::uint64_t seed, const wgs84::Llh& reference,
                                 const GpsTime& reference_time)
    : spec_(spec), reference_(reference), reference_time_(reference_time) {
  if (spec_.model != IonosphereTruthSpec::Model::thin_shell || spec_.disturbance_rms <= 0.0) return;
  // Medium-scale travelling ionospheric disturbances: wavelengths of a few hundred km,
  // periods of 15-60 min, a few percent of the TEC (Hernandez-Pajares et al. 2006,
  // "Medium-scale traveling ionospheric disturbances affecting GPS measurements").
  constexpr int kWaves = 3;
  auto rng = error_rng(seed, ErrorSource::ionosphere);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < kWaves; ++i) {
    Wave w;
    const double wavelength_m = 150e3 + 250e3 * unit(rng);
    const double period_s = 900.0 + 2700.0 * unit(rng);
    const double heading_rad = 2.0 * kPi * unit(rng);
    w.k_east_radpm = 2.0 * kPi / wavelength_m * std::sin(heading_rad);
    w.k_north_radpm = 2.0 * kPi / wavelength_m * std::cos(heading_rad);
    w.omega_radps = 2.0 * kPi / period_s;
    w.phase_rad = 2.0 * kPi * unit(rng);
    w.amplitude = spec_.disturbance_rms * std::sqrt(2.0 / kWaves);  // RMS of the sum = disturbance_rms
    waves_.push_back(w);
  }
}

IonosphereSample IonosphereTruth::thin_shell(const wgs84::Llh& rx, double azimuth_rad, double elevation_rad,
                                             const GpsTime& t) const {
  const double el = std::max(elevation_rad, 0.0);
  const double r_ratio = kEarthRadius_m / (kEarthRadius_m + spec_.shell_height_m);
  // Pierce point of the line of sight on the shell (spherical Earth).
  const double psi = kPi / 2.0 - el - std::asin(r_ratio * std::cos(el));
  const double sin_lat =
      std::sin(rx.lat_rad) * std::cos(psi) + std::cos(rx.lat_rad) * std::sin(psi) * std::cos(azimuth_rad);
  const double lat_ipp = std::asin(std::clamp(sin_lat, -1.0, 1.0));
  const double lon_ipp =
      rx.lon_rad + std::asin(std::clamp(std::sin(psi) * std::sin(azimuth_rad) / std::cos(lat_ipp), -1.0, 1.0));

  double local_time_h = std::fmod(t.sow / 3600.0 + lon_ipp / kPi * 12.0, 24.0);
  if (local_time_h < 0.0) local_time_h += 24.0;
  const double crest_vtec =
      spec_.night_vtec_tecu + (spec_.day_vtec_tecu - spec_.night_vtec_tecu) * diurnal_shape(local_time_h);
  double vtec = crest_vtec * latitude_profile(geomagnetic_latitude_rad(lat_ipp, lon_ipp));

  if (!waves_.empty()) {
    const double east_m = kEarthRadius_m * wrap_pi(lon_ipp - reference_.lon_rad) * std::cos(reference_.lat_rad);
    const double north_m = kEarthRadius_m * (lat_ipp - reference_.lat_rad);
    const double dt_s = t.seconds_since(reference_time_);
    double modulation = 0.0;
    for (const Wave& w : waves_)
      modulation += w.amplitude *
                    std::sin(w.k_east_radpm * east_m + w.k_north_radpm * north_m - w.omega_radps * dt_s + w.phase_rad);
    vtec *= 1.0 + modulation;
  }

  IonosphereSample s;
  s.vtec_tecu = spec_.vtec_scale * vtec;
  s.mapping = single_layer_mapping(el, spec_.shell_height_m);
  s.delay_m = l1_delay_m_from_tecu(s.vtec_tecu * s.mapping);
  return s;
}

double IonosphereTruth::delay_m(double klobuchar_m, const wgs84::Llh& rx, double azimuth_rad, double elevation_rad,
                                const GpsTime& t) const {
  if (spec_.model == IonosphereTruthSpec::Model::klobuchar) return spec_.vtec_scale * klobuchar_m;
  return thin_shell(rx, azimuth_rad, elevation_rad, t).delay_m;
}

}  // namespace deepnav
