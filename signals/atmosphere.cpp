#include "signals/atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ins/wgs84.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {

namespace {

struct AzEl {
  double azimuth_rad;
  double elevation_rad;
};

/// Look angles from the receiver's local east/north/up frame (geodetic vertical).
AzEl look_angles(const wgs84::Llh& rx, const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& r_sat_ecef_m) {
  const double sl = std::sin(rx.lat_rad), cl = std::cos(rx.lat_rad);
  const double so = std::sin(rx.lon_rad), co = std::cos(rx.lon_rad);
  const Eigen::Vector3d d = r_sat_ecef_m - r_rx_ecef_m;
  const double norm = d.norm();
  if (!(norm > 0.0)) throw std::invalid_argument("look angles: satellite and receiver positions coincide");
  const Eigen::Vector3d u = d / norm;
  const double east = -so * u.x() + co * u.y();
  const double north = -sl * co * u.x() - sl * so * u.y() + cl * u.z();
  const double up = cl * co * u.x() + cl * so * u.y() + sl * u.z();
  double az = std::atan2(east, north);
  if (az < 0.0) az += 2.0 * gps::kPi;
  return {az, std::asin(std::clamp(up, -1.0, 1.0))};
}

}  // namespace

double klobuchar_delay_s(const IonoParameters& iono, double lat_rad, double lon_rad, double azimuth_rad,
                         double elevation_rad, double t_sow) {
  if (!iono.valid) throw std::invalid_argument("klobuchar_delay_s: no valid ionosphere parameters (alpha/beta)");
  // The model works in semicircles; trigonometric functions take semicircles times pi.
  const double pi = gps::kPi;
  const double el = std::max(elevation_rad, 0.0) / pi;
  const double phi_u = lat_rad / pi;
  const double lam_u = lon_rad / pi;

  const double psi = 0.0137 / (el + 0.11) - 0.022;  // Earth-centred angle to the pierce point
  const double phi_i = std::clamp(phi_u + psi * std::cos(azimuth_rad), -0.416, 0.416);
  const double lam_i = lam_u + psi * std::sin(azimuth_rad) / std::cos(phi_i * pi);
  const double phi_m = phi_i + 0.064 * std::cos((lam_i - 1.617) * pi);  // geomagnetic latitude

  double t_local = 4.32e4 * lam_i + t_sow;
  t_local = std::fmod(t_local, 86400.0);
  if (t_local < 0.0) t_local += 86400.0;

  const double slant_factor = 1.0 + 16.0 * std::pow(0.53 - el, 3);
  double amp = 0.0, per = 0.0, phi_n = 1.0;
  for (int n = 0; n < 4; ++n) {
    amp += iono.alpha[static_cast<std::size_t>(n)] * phi_n;
    per += iono.beta[static_cast<std::size_t>(n)] * phi_n;
    phi_n *= phi_m;
  }
  amp = std::max(amp, 0.0);
  per = std::max(per, 72000.0);

  const double x = 2.0 * pi * (t_local - 50400.0) / per;
  constexpr double kNightDelay_s = 5e-9;
  if (std::abs(x) >= 1.57) return slant_factor * kNightDelay_s;
  return slant_factor * (kNightDelay_s + amp * (1.0 - x * x / 2.0 + x * x * x * x / 24.0));
}

double klobuchar_delay_m(const IonoParameters& iono, double lat_rad, double lon_rad, double azimuth_rad,
                         double elevation_rad, double t_sow) {
  return gps::kSpeedOfLight_mps * klobuchar_delay_s(iono, lat_rad, lon_rad, azimuth_rad, elevation_rad, t_sow);
}

double klobuchar_delay_m(const IonoParameters& iono, const Eigen::Vector3d& r_rx_ecef_m,
                         const Eigen::Vector3d& r_sat_ecef_m, double t_sow) {
  const wgs84::Llh rx = wgs84::ecef_to_llh(r_rx_ecef_m);
  const AzEl ae = look_angles(rx, r_rx_ecef_m, r_sat_ecef_m);
  return klobuchar_delay_m(iono, rx.lat_rad, rx.lon_rad, ae.azimuth_rad, ae.elevation_rad, t_sow);
}

TroposphereZenithDelay saastamoinen_zenith_delay(double lat_rad, double height_m) {
  // International Standard Atmosphere: troposphere lapse rate up to 11 km, isothermal above.
  const double h = std::max(height_m, -500.0);
  double pressure_hpa = 0.0, temperature_k = 0.0;
  if (h <= 11000.0) {
    pressure_hpa = 1013.25 * std::pow(1.0 - 2.25577e-5 * h, 5.25588);
    temperature_k = 288.15 - 6.5e-3 * h;
  } else {
    pressure_hpa = 226.32 * std::exp(-1.5769e-4 * (h - 11000.0));
    temperature_k = 216.65;
  }
  // Water vapour partial pressure at 70 % relative humidity (saturation formula as in RTKLIB).
  constexpr double kRelativeHumidity = 0.7;
  const double vapour_hpa =
      6.108 * kRelativeHumidity * std::exp((17.15 * temperature_k - 4684.0) / (temperature_k - 38.45));

  TroposphereZenithDelay z;
  z.hydrostatic_m = 0.0022768 * pressure_hpa / (1.0 - 0.00266 * std::cos(2.0 * lat_rad) - 0.00028 * h / 1000.0);
  z.wet_m = 0.002277 * (1255.0 / temperature_k + 0.05) * vapour_hpa;
  return z;
}

double troposphere_mapping(double elevation_rad) {
  const double s = std::sin(std::max(elevation_rad, 0.0));
  return 1.001 / std::sqrt(0.002001 + s * s);
}

double troposphere_delay_m(double lat_rad, double height_m, double elevation_rad) {
  return saastamoinen_zenith_delay(lat_rad, height_m).total_m() * troposphere_mapping(elevation_rad);
}

double troposphere_delay_m(const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& r_sat_ecef_m) {
  const wgs84::Llh rx = wgs84::ecef_to_llh(r_rx_ecef_m);
  const AzEl ae = look_angles(rx, r_rx_ecef_m, r_sat_ecef_m);
  return troposphere_delay_m(rx.lat_rad, rx.height_m, ae.elevation_rad);
}

}  // namespace deepnav
