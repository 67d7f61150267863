#include "ins/frames.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace deepnav {

Eigen::Matrix3d C_n_e(double lat_rad, double lon_rad) {
  const double sl = std::sin(lat_rad), cl = std::cos(lat_rad);
  const double so = std::sin(lon_rad), co = std::cos(lon_rad);
  Eigen::Matrix3d c;
  c << -sl * co, -so, -cl * co,  //
      -sl * so, co, -cl * so,    //
      cl, 0.0, -sl;
  return c;
}

Eigen::Matrix3d C_e_n(double lat_rad, double lon_rad) { return C_n_e(lat_rad, lon_rad).transpose(); }

Eigen::Vector3d ecef_to_ned_vector(const wgs84::Llh& at, const Eigen::Vector3d& x_ecef) {
  return C_e_n(at.lat_rad, at.lon_rad) * x_ecef;
}

Eigen::Vector3d ned_to_ecef_vector(const wgs84::Llh& at, const Eigen::Vector3d& x_ned) {
  return C_n_e(at.lat_rad, at.lon_rad) * x_ned;
}

Eigen::Vector3d ned_offset_m(const Eigen::Vector3d& r_reference_ecef_m, const Eigen::Vector3d& r_target_ecef_m) {
  return ecef_to_ned_vector(wgs84::ecef_to_llh(r_reference_ecef_m), r_target_ecef_m - r_reference_ecef_m);
}

Eigen::Vector3d earth_rate_ned_radps(double lat_rad) {
  return {wgs84::kEarthRate_radps * std::cos(lat_rad), 0.0, -wgs84::kEarthRate_radps * std::sin(lat_rad)};
}

Eigen::Vector3d transport_rate_ned_radps(const wgs84::Llh& at, const Eigen::Vector3d& v) {
  // w_en_n = [lon' cos L, -lat', -lon' sin L] with lat' = vN/(R_M+h), lon' = vE/((R_N+h) cos L).
  const double rm_h = wgs84::meridian_radius_m(at.lat_rad) + at.height_m;
  const double rn_h = wgs84::transverse_radius_m(at.lat_rad) + at.height_m;
  return {v.y() / rn_h, -v.x() / rm_h, -v.y() * std::tan(at.lat_rad) / rn_h};
}

Eigen::Vector3d transport_rate_derivative_ned_radps2(const wgs84::Llh& at, const Eigen::Vector3d& v,
                                                     const Eigen::Vector3d& a) {
  const double lat = at.lat_rad;
  const double sl = std::sin(lat), cl = std::cos(lat);
  const double e2 = wgs84::kEccentricitySq;
  const double den = 1.0 - e2 * sl * sl;
  const double rm = wgs84::meridian_radius_m(lat);
  const double rn = wgs84::transverse_radius_m(lat);
  const double rm_h = rm + at.height_m;
  const double rn_h = rn + at.height_m;
  const double lat_dot = v.x() / rm_h;
  const double h_dot = -v.z();
  // dR/dlat from R_N = a/sqrt(den) and R_M = a(1-e2)/den^1.5.
  const double drn_dt = rn * e2 * sl * cl / den * lat_dot;
  const double drm_dt = 3.0 * rm * e2 * sl * cl / den * lat_dot;
  // w = [vE/rn_h, -vN/rm_h, -vE tanL/rn_h], differentiated term by term.
  const double d_x = a.y() / rn_h - v.y() * (drn_dt + h_dot) / (rn_h * rn_h);
  const double d_y = -a.x() / rm_h + v.x() * (drm_dt + h_dot) / (rm_h * rm_h);
  const double tan_l = sl / cl;
  const double dtan_dt = lat_dot / (cl * cl);
  const double d_z = -(a.y() * tan_l + v.y() * dtan_dt) / rn_h + v.y() * tan_l * (drn_dt + h_dot) / (rn_h * rn_h);
  return {d_x, d_y, d_z};
}

LookAngles look_angles(const wgs84::Llh& receiver, const Eigen::Vector3d& r_receiver_ecef_m,
                       const Eigen::Vector3d& r_target_ecef_m) {
  const Eigen::Vector3d los_ned = ecef_to_ned_vector(receiver, r_target_ecef_m - r_receiver_ecef_m);
  const double range = los_ned.norm();
  if (!(range > 0.0)) {
    throw std::invalid_argument("look_angles: receiver and target positions coincide (or are not finite)");
  }
  LookAngles out;
  out.elevation_rad = std::asin(std::clamp(-los_ned.z() / range, -1.0, 1.0));
  double az = std::atan2(los_ned.y(), los_ned.x());
  if (az < 0.0) az += 2.0 * std::numbers::pi;
  out.azimuth_rad = az >= 2.0 * std::numbers::pi ? 0.0 : az;
  return out;
}

LookAngles look_angles(const Eigen::Vector3d& r_receiver_ecef_m, const Eigen::Vector3d& r_target_ecef_m) {
  return look_angles(wgs84::ecef_to_llh(r_receiver_ecef_m), r_receiver_ecef_m, r_target_ecef_m);
}

}  // namespace deepnav
