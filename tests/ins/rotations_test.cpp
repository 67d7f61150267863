#include "ins/rotations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Rotations, KnownAngles) {
  // Yaw 90 deg: the body's forward axis points east.
  const Eigen::Matrix3d yaw = dcm_from_euler({0.0, 0.0, 90.0 * kDeg});
  EXPECT_TRUE((yaw * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  // Pitch 90 deg (nose up): forward points up, i.e. -down.
  const Eigen::Matrix3d pitch = dcm_from_euler({0.0, 90.0 * kDeg, 0.0});
  EXPECT_TRUE((pitch * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
  // Roll 90 deg (right wing down): the right axis points down.
  const Eigen::Matrix3d roll = dcm_from_euler({90.0 * kDeg, 0.0, 0.0});
  EXPECT_TRUE((roll * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  // The 3-2-1 product, written out.
  const EulerAngles e{10.0 * kDeg, -20.0 * kDeg, 30.0 * kDeg};
  const double cr = std::cos(e.roll_rad), sr = std::sin(e.roll_rad);
  const double cp = std::cos(e.pitch_rad), sp = std::sin(e.pitch_rad);
  const double cy = std::cos(e.yaw_rad), sy = std::sin(e.yaw_rad);
  Eigen::Matrix3d expected;
  expected << cp * cy, -cr * sy + sr * sp * cy, sr * sy + cr * sp * cy,  //
      cp * sy, cr * cy + sr * sp * sy, -sr * cy + cr * sp * sy,          //
      -sp, sr * cp, cr * cp;
  EXPECT_TRUE(dcm_from_euler(e).isApprox(expected, 1e-14));
}

TEST(Rotations, EulerDcmQuaternionRoundTrips) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ang(-179.9, 179.9), pit(-89.9, 89.9);
  for (int i = 0; i < 500; ++i) {
    const EulerAngles e{ang(rng) * kDeg, pit(rng) * kDeg, ang(rng) * kDeg};
    const EulerAngles from_dcm = euler_from_dcm(dcm_from_euler(e));
    const EulerAngles from_q = euler_from_quaternion(quaternion_from_euler(e));
    for (const EulerAngles& b : {from_dcm, from_q}) {
      EXPECT_NEAR(b.roll_rad, e.roll_rad, 1e-9);
      EXPECT_NEAR(b.pitch_rad, e.pitch_rad, 1e-9);
      EXPECT_NEAR(b.yaw_rad, e.yaw_rad, 1e-9);
    }
    EXPECT_TRUE(quaternion_from_euler(e).toRotationMatrix().isApprox(dcm_from_euler(e), 1e-12));
  }
}

TEST(Rotations, GimbalLockKeepsTheRotation) {
  const EulerAngles e{30.0 * kDeg, 90.0 * kDeg, 50.0 * kDeg};
  const EulerAngles back = euler_from_dcm(dcm_from_euler(e));
  EXPECT_DOUBLE_EQ(back.roll_rad, 0.0);
  EXPECT_TRUE(dcm_from_euler(back).isApprox(dcm_from_euler(e), 1e-9));
}

TEST(Rotations, SkewIsTheCrossProduct) {
  const Eigen::Vector3d a(1.0, -2.0, 3.5), b(-0.5, 4.0, 2.0);
  EXPECT_TRUE((skew(a) * b).isApprox(a.cross(b), 1e-15));
  EXPECT_TRUE((skew(a) + skew(a).transpose()).isZero(0.0));
}

TEST(Rotations, RotationVectorIsExactRodrigues) {
  const Eigen::Vector3d rv(0.3, -1.1, 2.0);
  const double a = rv.norm();
  const Eigen::Matrix3d k = skew(rv / a);
  const Eigen::Matrix3d rodrigues = Eigen::Matrix3d::Identity() + std::sin(a) * k + (1.0 - std::cos(a)) * k * k;
  EXPECT_TRUE(dcm_from_rotation_vector(rv).isApprox(rodrigues, 1e-14));
  EXPECT_TRUE(rotation_vector_from_quaternion(quaternion_from_rotation_vector(rv)).isApprox(rv, 1e-12));
  // Tiny and zero angles: first-order I + [rv x] is exact to double precision.
  const Eigen::Vector3d tiny(1e-10, -2e-10, 3e-10);
  EXPECT_TRUE(dcm_from_rotation_vector(tiny).isApprox(Eigen::Matrix3d::Identity() + skew(tiny), 1e-15));
  EXPECT_TRUE(dcm_from_rotation_vector(Eigen::Vector3d::Zero()).isIdentity(0.0));
  // Just either side of the series switch-over the two branches agree.
  const Eigen::Vector3d below = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0 * 0.999e-8;
  const Eigen::Vector3d above = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0 * 1.001e-8;
  EXPECT_NEAR(rotation_vector_from_quaternion(quaternion_from_rotation_vector(below)).norm(), 0.999e-8, 1e-20);
  EXPECT_NEAR(rotation_vector_from_quaternion(quaternion_from_rotation_vector(above)).norm(), 1.001e-8, 1e-20);
}

TEST(Rotations, QuaternionNormalisation) {
  const Eigen::Quaterniond q(-2.0, 0.2, 0.4, -1.0);
  const Eigen::Quaterniond n = normalized_quaternion(q);
  EXPECT_NEAR(n.norm(), 1.0, 1e-15);
  EXPECT_GE(n.w(), 0.0);
  EXPECT_TRUE(n.toRotationMatrix().isApprox(q.normalized().toRotationMatrix(), 1e-14));
  EXPECT_THROW(normalized_quaternion(Eigen::Quaterniond(0.0, 0.0, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(normalized_quaternion(Eigen::Quaterniond(NAN, 0.0, 0.0, 1.0)), std::invalid_argument);
}

TEST(Rotations, BodyRateMatchesDcmDerivative) {
  // C_b_n' = C_b_n [w_nb_b x]: check the Euler-rate kinematics by central differences.
  const auto euler_at = [](double t) {
    return EulerAngles{0.3 * std::sin(1.3 * t), 0.2 * std::cos(0.7 * t) - 0.1, 0.5 * t * t - 1.0};
  };
  const auto rate_at = [](double t) {
    return Eigen::Vector3d(0.39 * std::cos(1.3 * t), -0.14 * std::sin(0.7 * t), 1.0 * t);
  };
  const auto accel_at = [](double t) {
    return Eigen::Vector3d(-0.507 * std::sin(1.3 * t), -0.098 * std::cos(0.7 * t), 1.0);
  };
  const double h = 1e-5;
  for (double t : {0.0, 0.4, 1.7, 3.1}) {
    const Eigen::Matrix3d dc = (dcm_from_euler(euler_at(t + h)) - dcm_from_euler(euler_at(t - h))) / (2.0 * h);
    const Eigen::Matrix3d w_skew = dcm_from_euler(euler_at(t)).transpose() * dc;
    const Eigen::Vector3d w(w_skew(2, 1), w_skew(0, 2), w_skew(1, 0));
    EXPECT_TRUE(body_rate_from_euler_rates(euler_at(t), rate_at(t)).isApprox(w, 1e-8)) << t;

    const EulerKinematics k{euler_at(t), rate_at(t), accel_at(t)};
    const Eigen::Vector3d dw_fd = (body_rate_from_euler_rates(euler_at(t + h), rate_at(t + h)) -
                                   body_rate_from_euler_rates(euler_at(t - h), rate_at(t - h))) /
                                  (2.0 * h);
    EXPECT_LT((body_rate_derivative_from_euler(k) - dw_fd).norm(), 1e-8) << t;
  }
}

TEST(Rotations, WrapPi) {
  EXPECT_NEAR(wrap_pi(3.0 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(wrap_pi(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(wrap_pi(-0.5), -0.5, 1e-15);
  EXPECT_NEAR(wrap_pi(7.0), 7.0 - 2.0 * std::numbers::pi, 1e-12);
}

}  // namespace
}  // namespace deepnav
