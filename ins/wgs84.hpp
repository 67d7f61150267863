#pragma once
// WGS-84 ellipsoid, Earth rotation and normal gravity; ECEF <-> geodetic.
#include <Eigen/Core>

namespace deepnav::wgs84 {

inline constexpr double kSemiMajorAxis_m = 6378137.0;
inline constexpr double kFlattening = 1.0 / 298.257223563;
inline constexpr double kSemiMinorAxis_m = kSemiMajorAxis_m * (1.0 - kFlattening);
inline constexpr double kEccentricitySq = kFlattening * (2.0 - kFlattening);
inline constexpr double kEarthRate_radps = 7.2921151467e-5;  // also IS-GPS-200's value
inline constexpr double kGM_m3ps2 = 3.986004418e14;
inline constexpr double kSpeedOfLight_mps = 299792458.0;

/// Geodetic position: latitude and longitude in radians, height above the ellipsoid in metres.
struct Llh {
  double lat_rad = 0.0;
  double lon_rad = 0.0;
  double height_m = 0.0;
};

Eigen::Vector3d llh_to_ecef(const Llh& llh);
/// Exact closed-form inverse (Vermeille 2004); valid everywhere except at the Earth's centre.
Llh ecef_to_llh(const Eigen::Vector3d& r_ecef);

/// Meridian (north-south) radius of curvature R_M.
double meridian_radius_m(double lat_rad);
/// Prime-vertical (east-west) radius of curvature R_N.
double transverse_radius_m(double lat_rad);

/// Somigliana normal gravity with the free-air height correction (m/s^2, positive down).
double normal_gravity_mps2(double lat_rad, double height_m);

}  // namespace deepnav::wgs84
