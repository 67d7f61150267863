#include "ins/wgs84.hpp"

#include <cmath>

namespace deepnav::wgs84 {

Eigen::Vector3d llh_to_ecef(const Llh& llh) {
  const double sin_lat = std::sin(llh.lat_rad);
  const double cos_lat = std::cos(llh.lat_rad);
  const double rn = transverse_radius_m(llh.lat_rad);
  return {(rn + llh.height_m) * cos_lat * std::cos(llh.lon_rad), (rn + llh.height_m) * cos_lat * std::sin(llh.lon_rad),
          (rn * (1.0 - kEccentricitySq) + llh.height_m) * sin_lat};
}

Llh ecef_to_llh(const Eigen::Vector3d& r) {
  // Vermeille (2004), "Computing geodetic coordinates from geocentric coordinates".
  constexpr double a = kSemiMajorAxis_m;
  constexpr double e2 = kEccentricitySq;
  constexpr double e4 = e2 * e2;
  const double p = (r.x() * r.x() + r.y() * r.y()) / (a * a);
  const double q = (1.0 - e2) / (a * a) * r.z() * r.z();
  const double rr = (p + q - e4) / 6.0;
  const double s = e4 * p * q / (4.0 * rr * rr * rr);
  const double t = std::cbrt(1.0 + s + std::sqrt(s * (2.0 + s)));
  const double u = rr * (1.0 + t + 1.0 / t);
  const double v = std::sqrt(u * u + e4 * q);
  const double w = e2 * (u + v - q) / (2.0 * v);
  const double k = std::sqrt(u + v + w * w) - w;
  const double d = k * std::hypot(r.x(), r.y()) / (k + e2);
  Llh out;
  out.lat_rad = 2.0 * std::atan2(r.z(), d + std::hypot(d, r.z()));
  out.lon_rad = std::atan2(r.y(), r.x());
  out.height_m = (k + e2 - 1.0) / k * std::hypot(d, r.z());
  return out;
}

double meridian_radius_m(double lat_rad) {
  const double s = std::sin(lat_rad);
  const double den = 1.0 - kEccentricitySq * s * s;
  return kSemiMajorAxis_m * (1.0 - kEccentricitySq) / (den * std::sqrt(den));
}

double transverse_radius_m(double lat_rad) {
  const double s = std::sin(lat_rad);
  return kSemiMajorAxis_m / std::sqrt(1.0 - kEccentricitySq * s * s);
}

double normal_gravity_mps2(double lat_rad, double height_m) {
  // Somigliana formula on the ellipsoid, then the second-order free-air term
  // (Groves, Principles of GNSS, Inertial and Multisensor Navigation, eq. 2.134).
  constexpr double g_equator = 9.7803253359;
  constexpr double k_somigliana = 1.931853e-3;
  const double s2 = std::sin(lat_rad) * std::sin(lat_rad);
  const double g0 = g_equator * (1.0 + k_somigliana * s2) / std::sqrt(1.0 - kEccentricitySq * s2);
  constexpr double m =
      kEarthRate_radps * kEarthRate_radps * kSemiMajorAxis_m * kSemiMajorAxis_m * kSemiMinorAxis_m / kGM_m3ps2;
  const double h_over_a = height_m / kSemiMajorAxis_m;
  return g0 * (1.0 - 2.0 / kSemiMajorAxis_m * (1.0 + kFlattening + m - 2.0 * kFlattening * s2) * height_m +
               3.0 * h_over_a * h_over_a);
}

}  // namespace deepnav::wgs84
