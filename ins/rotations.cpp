#include "ins/rotations.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace deepnav {

Eigen::Quaterniond quaternion_from_euler(const EulerAngles& e) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(e.yaw_rad, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(e.pitch_rad, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(e.roll_rad, Eigen::Vector3d::UnitX()));
}

Eigen::Matrix3d dcm_from_euler(const EulerAngles& e) { return quaternion_from_euler(e).toRotationMatrix(); }

EulerAngles euler_from_dcm(const Eigen::Matrix3d& C) {
  // C(2,0) = -sin(pitch) and |(C(2,1), C(2,2))| = cos(pitch): atan2 stays accurate near
  // +-90 deg, where asin(-C(2,0)) loses half the digits.
  EulerAngles e;
  const double s_pitch = std::clamp(-C(2, 0), -1.0, 1.0);
  e.pitch_rad = std::atan2(s_pitch, std::hypot(C(2, 1), C(2, 2)));
  if (std::abs(s_pitch) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw -/+ roll is observable; report it all as yaw.
    e.roll_rad = 0.0;
    e.yaw_rad = std::atan2(-C(0, 1), C(1, 1));
  } else {
    e.roll_rad = std::atan2(C(2, 1), C(2, 2));
    e.yaw_rad = std::atan2(C(1, 0), C(0, 0));
  }
  return e;
}

EulerAngles euler_from_quaternion(const Eigen::Quaterniond& q_b_n) {
  return euler_from_dcm(q_b_n.normalized().toRotationMatrix());
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& rot_vec_rad) {
  const double angle = rot_vec_rad.norm();
  if (angle < 1e-8) {
    // Series of cos(a/2) and sin(a/2)/a: exact to double precision this close to zero,
    // where the axis itself is undefined.
    const double half_sq = 0.25 * angle * angle;
    Eigen::Quaterniond q(1.0 - 0.5 * half_sq, 0.0, 0.0, 0.0);
    q.vec() = (0.5 - half_sq / 12.0) * rot_vec_rad;
    return q.normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, rot_vec_rad / angle));
}

Eigen::Matrix3d dcm_from_rotation_vector(const Eigen::Vector3d& rot_vec_rad) {
  return quaternion_from_rotation_vector(rot_vec_rad).toRotationMatrix();
}

Eigen::Vector3d rotation_vector_from_quaternion(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd aa(normalized_quaternion(q));
  return aa.angle() * aa.axis();
}

Eigen::Quaterniond normalized_quaternion(const Eigen::Quaterniond& q) {
  const double n = q.norm();
  if (!std::isfinite(n) || n == 0.0) {
    throw std::invalid_argument("normalized_quaternion: quaternion is zero or not finite");
  }
  Eigen::Quaterniond out(q.coeffs() / n);
  if (out.w() < 0.0) out.coeffs() = -out.coeffs();
  return out;
}

Eigen::Vector3d body_rate_from_euler_rates(const EulerAngles& e, const Eigen::Vector3d& r) {
  const double sr = std::sin(e.roll_rad), cr = std::cos(e.roll_rad);
  const double sp = std::sin(e.pitch_rad), cp = std::cos(e.pitch_rad);
  // w = Rx(roll)^T [roll' 0 0] + Rx^T Ry(pitch)^T [0 pitch' 0] + ... for yaw.
  return {r.x() - r.z() * sp,            //
          r.y() * cr + r.z() * sr * cp,  //
          -r.y() * sr + r.z() * cr * cp};
}

Eigen::Vector3d body_rate_derivative_from_euler(const EulerKinematics& k) {
  const double sr = std::sin(k.angles.roll_rad), cr = std::cos(k.angles.roll_rad);
  const double sp = std::sin(k.angles.pitch_rad), cp = std::cos(k.angles.pitch_rad);
  const double dr = k.rate_radps.x(), dp = k.rate_radps.y(), dy = k.rate_radps.z();
  const double ddr = k.accel_radps2.x(), ddp = k.accel_radps2.y(), ddy = k.accel_radps2.z();
  // Product rule applied to body_rate_from_euler_rates.
  return {ddr - ddy * sp - dy * cp * dp, ddp * cr - dp * sr * dr + ddy * sr * cp + dy * (cr * dr * cp - sr * sp * dp),
          -ddp * sr - dp * cr * dr + ddy * cr * cp + dy * (-sr * dr * cp - cr * sp * dp)};
}

double wrap_pi(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  double w = std::remainder(a, two_pi);  // in [-pi, pi]
  if (w <= -std::numbers::pi) w += two_pi;
  return w;
}

}  // namespace deepnav
