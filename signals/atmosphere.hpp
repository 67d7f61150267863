#pragma once
// Broadcast ionosphere (Klobuchar, IS-GPS-200 20.3.3.5.2.5) and a standard troposphere
// (Saastamoinen zenith delays from a standard atmosphere, Black & Eisner mapping function),
// both as delays of the L1 C/A code.
#include <Eigen/Core>

#include "signals/iono_utc.hpp"

namespace deepnav {

/// Klobuchar L1 group delay (seconds) for a receiver at geodetic latitude/longitude (radians),
/// a satellite at azimuth/elevation (radians, elevation below 0 is taken as 0) and GPS time
/// of week t_sow. Throws std::invalid_argument when iono.valid is false.
double klobuchar_delay_s(const IonoParameters& iono, double lat_rad, double lon_rad, double azimuth_rad,
                         double elevation_rad, double t_sow);
/// The same as a range delay in metres (c times the delay).
double klobuchar_delay_m(const IonoParameters& iono, double lat_rad, double lon_rad, double azimuth_rad,
                         double elevation_rad, double t_sow);
/// The same for a receiver and a satellite given in ECEF (look angles computed here).
double klobuchar_delay_m(const IonoParameters& iono, const Eigen::Vector3d& r_rx_ecef_m,
                         const Eigen::Vector3d& r_sat_ecef_m, double t_sow);

struct TroposphereZenithDelay {
  double hydrostatic_m = 0.0;
  double wet_m = 0.0;
  double total_m() const { return hydrostatic_m + wet_m; }
};

/// Saastamoinen (1972) zenith delays with meteorology from a standard atmosphere at the
/// receiver height: ISA pressure and temperature (15 degC, 1013.25 hPa at sea level,
/// -6.5 K/km up to 11 km, isothermal above) and 70 % relative humidity.
TroposphereZenithDelay saastamoinen_zenith_delay(double lat_rad, double height_m);

/// Black & Eisner (1984) mapping function 1.001 / sqrt(0.002001 + sin^2(el)), the one of
/// RTCA DO-229: 1 at the zenith, close to 1/sin(el) above 15 deg, finite (22.4) at the
/// horizon. Elevations below 0 are taken as 0.
double troposphere_mapping(double elevation_rad);

/// Slant troposphere delay (m): Saastamoinen zenith total times the mapping function.
double troposphere_delay_m(double lat_rad, double height_m, double elevation_rad);
/// The same for a receiver and a satellite given in ECEF.
double troposphere_delay_m(const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& r_sat_ecef_m);

}  // namespace deepnav
