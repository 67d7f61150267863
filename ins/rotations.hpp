#pragma once
// Attitude representations in the papers' convention [docs/references.md] and conversions between them.
//
// Body axes: x forward, y right, z down. Navigation frame: NED. Euler angles are the
// 3-2-1 (yaw-pitch-roll) sequence: C_b_n = Rz(yaw) * Ry(pitch) * Rx(roll), where
// Rk(a) is the right-handed rotation about axis k by angle a (body -> NED, active).
// Roll phi in (-pi, pi], pitch theta in [-pi/2, pi/2], yaw psi in (-pi, pi].
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace deepnav {

struct EulerAngles {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
};

/// Euler angles with their first and second time derivatives (angle rates are the
/// derivatives of the angles themselves, not body rates).
struct EulerKinematics {
  EulerAngles angles;
  Eigen::Vector3d rate_radps = Eigen::Vector3d::Zero();    ///< [roll', pitch', yaw']
  Eigen::Vector3d accel_radps2 = Eigen::Vector3d::Zero();  ///< [roll'', pitch'', yaw'']
};

Eigen::Matrix3d dcm_from_euler(const EulerAngles& e);
Eigen::Quaterniond quaternion_from_euler(const EulerAngles& e);
/// Inverse of dcm_from_euler. At pitch = +-90 deg (gimbal lock) roll is set to zero and
/// the whole heading goes into yaw.
EulerAngles euler_from_dcm(const Eigen::Matrix3d& C_b_n);
EulerAngles euler_from_quaternion(const Eigen::Quaterniond& q_b_n);

/// [v x]: skew(a) * b == a.cross(b).
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

/// Exact rotation for a rotation vector (axis * angle, Rodrigues), valid for any angle
/// including zero.
Eigen::Matrix3d dcm_from_rotation_vector(const Eigen::Vector3d& rot_vec_rad);
Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& rot_vec_rad);
/// Inverse of the above, angle in [0, pi].
Eigen::Vector3d rotation_vector_from_quaternion(const Eigen::Quaterniond& q);

/// Unit quaternion with a non-negative scalar part (q and -q are the same rotation; the
/// canonical sign keeps comparisons and interpolation well behaved). Throws
/// std::invalid_argument for a zero or non-finite quaternion.
Eigen::Quaterniond normalized_quaternion(const Eigen::Quaterniond& q);

/// Body angular rate w_nb_b from the Euler angles and their rates (3-2-1 kinematics).
Eigen::Vector3d body_rate_from_euler_rates(const EulerAngles& e, const Eigen::Vector3d& euler_rate_radps);
/// Time derivative of the body rate above, from the Euler angles, rates and accelerations.
Eigen::Vector3d body_rate_derivative_from_euler(const EulerKinematics& k);

/// Wraps an angle into (-pi, pi].
double wrap_pi(double angle_rad);

}  // namespace deepnav
