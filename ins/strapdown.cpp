#include "ins/strapdown.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "ins/rotations.hpp"

namespace deepnav {
namespace {

// Radii of curvature from one sine (the per-step hot path).
struct Radii {
  double meridian_m;
  double transverse_m;
};
Radii radii_of_curvature(double sin_lat) {
  const double den = 1.0 - wgs84::kEccentricitySq * sin_lat * sin_lat;
  const double transverse = wgs84::kSemiMajorAxis_m / std::sqrt(den);
  return {transverse * (1.0 - wgs84::kEccentricitySq) / den, transverse};
}

void require_finite(const Eigen::Vector3d& v, const char* what, double t_s) {
  if (!v.allFinite()) {
    throw std::invalid_argument(std::string("strapdown: ") + what + " of the IMU sample at t = " + std::to_string(t_s) +
                                " s is not finite");
  }
}

}  // namespace

StrapdownNed::StrapdownNed(const NavState& initial) { reset(initial); }

void StrapdownNed::reset(const NavState& state) {
  state_ = state;
  state_.q_b_n.normalize();
  have_previous_ = false;
  previous_dv_ned_.setZero();
  previous_dlat_ = 0.0;
  previous_dh_ = 0.0;
}

void StrapdownNed::update(const ImuSample& sample) {
  const double dt = sample.t_s - state_.t_s;
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw std::invalid_argument("strapdown: IMU sample time " + std::to_string(sample.t_s) +
                                " s is not after the navigation state's time " + std::to_string(state_.t_s) + " s");
  }
  require_finite(sample.dtheta_b_rad, "dtheta", sample.t_s);
  require_finite(sample.dv_b_mps, "dv", sample.t_s);

  const Eigen::Vector3d dtheta = sample.dtheta_b_rad - gyro_bias_radps_ * dt;
  const Eigen::Vector3d dv = sample.dv_b_mps - accel_bias_mps2_ * dt;
  // Samples on either side of a gap are not adjacent: no coning/sculling across it,
  // and no extrapolation from the step before it.
  const bool adjacent = have_previous_ && dt <= 1.5 * previous_dt_s_;
  const double extrapolation = adjacent ? 0.5 * dt / previous_dt_s_ : 0.0;

  // Body rotation and body-frame velocity increment with coning / sculling.
  Eigen::Vector3d phi = dtheta;
  // Rotation compensation to third order: for a constant rate over the interval the
  // body-frame velocity change is dv + 1/2 dtheta x dv + 1/6 dtheta x (dtheta x dv) + ...;
  // the last term rectifies gravity under vibration and is kept.
  const Eigen::Vector3d dtheta_x_dv = dtheta.cross(dv);
  Eigen::Vector3d dv_b = dv + 0.5 * dtheta_x_dv + dtheta.cross(dtheta_x_dv) / 6.0;
  if (adjacent) {
    phi += previous_dtheta_.cross(dtheta) / 12.0;
    dv_b += (previous_dtheta_.cross(dv) + previous_dv_.cross(dtheta)) / 12.0;
  }

  // Navigation-frame terms at the middle of the interval.
  NavState& s = state_;
  const double lat_mid = s.llh.lat_rad + extrapolation * previous_dlat_;
  const double h_mid = s.llh.height_m + extrapolation * previous_dh_;
  const Eigen::Vector3d v_mid = s.v_ned_mps + extrapolation * previous_dv_ned_;
  const double sin_mid = std::sin(lat_mid), cos_mid = std::cos(lat_mid);
  const Radii radii = radii_of_curvature(sin_mid);
  const double r_north = radii.meridian_m + h_mid, r_east = radii.transverse_m + h_mid;
  const Eigen::Vector3d w_ie_n = wgs84::kEarthRate_radps * Eigen::Vector3d(cos_mid, 0.0, -sin_mid);
  const Eigen::Vector3d w_en_n(v_mid.y() / r_east, -v_mid.x() / r_north, -v_mid.y() * sin_mid / (cos_mid * r_east));
  const Eigen::Vector3d zeta = (w_ie_n + w_en_n) * dt;
  const Eigen::Vector3d g_n(0.0, 0.0, wgs84::normal_gravity_mps2(lat_mid, h_mid));

  // Velocity.
  const Eigen::Vector3d dv_n_sf = s.q_b_n * dv_b;
  const Eigen::Vector3d dv_ned =
      dv_n_sf - 0.5 * zeta.cross(dv_n_sf) + (g_n - (2.0 * w_ie_n + w_en_n).cross(v_mid)) * dt;
  const Eigen::Vector3d v_old = s.v_ned_mps;
  s.v_ned_mps += dv_ned;
  const Eigen::Vector3d v_avg = 0.5 * (v_old + s.v_ned_mps);

  // Position: height, latitude, longitude (trapezoidal on velocity).
  const double dh = -v_avg.z() * dt;
  const double dlat = v_avg.x() / r_north * dt;
  const double lat_avg = s.llh.lat_rad + 0.5 * dlat;
  s.llh.height_m += dh;
  s.llh.lat_rad += dlat;
  s.llh.lon_rad += v_avg.y() / (r_east * std::cos(lat_avg)) * dt;

  // Attitude: body rotation on the right, navigation-frame rotation on the left.
  s.q_b_n = quaternion_from_rotation_vector(-zeta) * s.q_b_n * quaternion_from_rotation_vector(phi);
  s.q_b_n.normalize();
  s.t_s = sample.t_s;

  have_previous_ = true;
  previous_dt_s_ = dt;
  previous_dtheta_ = dtheta;
  previous_dv_ = dv;
  previous_dv_ned_ = dv_ned;
  previous_dlat_ = dlat;
  previous_dh_ = dh;
}

void StrapdownNed::correct_position(const Eigen::Vector3d& dr_ned_m) {
  const double sin_lat = std::sin(state_.llh.lat_rad);
  const Radii radii = radii_of_curvature(sin_lat);
  const double h = state_.llh.height_m;
  state_.llh.lat_rad += dr_ned_m.x() / (radii.meridian_m + h);
  state_.llh.lon_rad += dr_ned_m.y() / ((radii.transverse_m + h) * std::cos(state_.llh.lat_rad));
  state_.llh.height_m -= dr_ned_m.z();
}

void StrapdownNed::correct_velocity(const Eigen::Vector3d& dv_ned_mps) { state_.v_ned_mps += dv_ned_mps; }

void StrapdownNed::correct_attitude(const Eigen::Vector3d& dpsi_ned_rad) {
  state_.q_b_n = (quaternion_from_rotation_vector(dpsi_ned_rad) * state_.q_b_n).normalized();
}

void StrapdownNed::set_bias_compensation(const Eigen::Vector3d& accel_bias_mps2,
                                         const Eigen::Vector3d& gyro_bias_radps) {
  accel_bias_mps2_ = accel_bias_mps2;
  gyro_bias_radps_ = gyro_bias_radps;
}

}  // namespace deepnav
