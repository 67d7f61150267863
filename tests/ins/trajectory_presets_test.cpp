#include "ins/sim/trajectory_presets.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "ins/frames.hpp"
#include "ins/rotations.hpp"

namespace deepnav {
namespace {

constexpr double kPi = 3.14159265358979323846;
const wgs84::Llh kStart{37.5 * kPi / 180.0, 127.0 * kPi / 180.0, 50.0};

/// Central difference of f at t (fourth order).
template <typename F>
Eigen::Vector3d derivative(F f, double t, double h) {
  return (f(t - 2 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2 * h)) / (12.0 * h);
}

class EveryPreset : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryPreset, DerivativesAreConsistent) {
  const auto traj = make_preset_trajectory(GetParam(), kStart, 0.3, 200.0);
  for (double t : {0.5, 13.7, 61.0, 149.9}) {
    const TrajectoryState s = traj->at(t);
    // Position -> velocity to 1e-6 relative (plus the round-off of differencing ECEF metres).
    const Eigen::Vector3d v_fd = derivative([&](double x) { return traj->at(x).r_ecef_m; }, t, 1e-2);
    EXPECT_LE((v_fd - s.v_ecef_mps).norm(), 1e-6 * s.v_ecef_mps.norm() + 2e-7) << GetParam() << " t=" << t;
    const Eigen::Vector3d a_fd = derivative([&](double x) { return traj->at(x).v_ecef_mps; }, t, 1e-2);
    EXPECT_LE((a_fd - s.a_ecef_mps2).norm(), 1e-6 * s.a_ecef_mps2.norm() + 1e-8) << GetParam() << " t=" << t;
    // Local NED velocity is the ECEF velocity rotated; its derivative is a_ned.
    const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
    EXPECT_LE((ned_to_ecef_vector(llh, s.v_ned_mps) - s.v_ecef_mps).norm(), 1e-9);
    const Eigen::Vector3d an_fd = derivative([&](double x) { return traj->at(x).v_ned_mps; }, t, 1e-2);
    EXPECT_LE((an_fd - s.a_ned_mps2).norm(), 1e-6 * s.a_ned_mps2.norm() + 1e-7) << GetParam() << " t=" << t;
    // Attitude -> body rate: the rotation over a short step matches w_nb_b.
    const double h = 1e-3;
    const Eigen::Quaterniond dq = traj->at(t - h).q_b_n.conjugate() * traj->at(t + h).q_b_n;
    const Eigen::Vector3d w_fd = rotation_vector_from_quaternion(dq) / (2 * h);
    EXPECT_LE((w_fd - s.w_nb_b_radps).norm(), 1e-7 + 1e-5 * s.w_nb_b_radps.norm()) << GetParam() << " t=" << t;
    const Eigen::Vector3d dw_fd = derivative([&](double x) { return traj->at(x).w_nb_b_radps; }, t, 1e-2);
    EXPECT_LE((dw_fd - s.dw_nb_b_radps2).norm(), 1e-6 + 1e-4 * s.dw_nb_b_radps2.norm()) << GetParam() << " t=" << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Presets, EveryPreset, ::testing::ValuesIn(preset_trajectory_names()), [](const auto& info) {
  std::string n = info.param;
  for (auto& c : n) c = (c == '-') ? '_' : c;
  return n;
});

/// Horizontal distance of the path's points from their centroid over one full turn.
void expect_circle(const std::string& name, double radius_m, double speed_mps) {
  const auto traj = make_preset_trajectory(name, kStart, 0.0, 200.0);
  const double period = 2 * kPi * radius_m / speed_mps;
  const Eigen::Vector3d r0 = traj->at(0).r_ecef_m;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  const int n = 64;
  for (int k = 0; k < n; ++k) centre += ned_offset_m(r0, traj->at(period * k / n).r_ecef_m) / n;
  for (int k = 0; k < n; ++k) {
    const TrajectoryState s = traj->at(period * k / n + 0.37);
    const Eigen::Vector3d d = ned_offset_m(r0, s.r_ecef_m) - centre;
    EXPECT_NEAR(std::hypot(d.x(), d.y()), radius_m, 1e-3 * radius_m) << name;
    EXPECT_NEAR(s.v_ned_mps.head<2>().norm(), speed_mps, 1e-3 * speed_mps) << name;
  }
}

TEST(TrajectoryPresets, CirclesHaveTheAskedRadiusAndSpeed) {
  expect_circle("land-circle", 87.27, 10.0 / 3.6);
  expect_circle("air-circle", 4422.0, 500.0 / 3.6);
  expect_circle("air-circle-x2", 2211.0, 500.0 / 3.6);
}

TEST(TrajectoryPresets, AircraftBankInCoordinatedTurns) {
  const auto traj = make_preset_trajectory("air-circle", kStart, 0.0, 200.0);
  const EulerAngles e = euler_from_quaternion(traj->at(50.0).q_b_n);
  const double v = 500.0 / 3.6;
  EXPECT_NEAR(e.roll_rad, std::atan(v * (kPi / 100.0) / 9.80665), 2e-3);
  // The yaw rate is the turn rate pi/100 rad/s.
  EXPECT_NEAR(traj->at(50.0).w_nb_b_radps.norm(), kPi / 100.0, 1e-4);
}

TEST(TrajectoryPresets, SShapeReversesTheBankSmoothly) {
  // air-s reverses its turn every 100 s; the bank blends over 4 s centred on the reversal.
  const auto traj = make_preset_trajectory("air-s", kStart, 0.0, 200.0);
  const double bank = std::atan(500.0 / 3.6 * (kPi / 100.0) / 9.80665);
  EXPECT_NEAR(euler_from_quaternion(traj->at(97.0).q_b_n).roll_rad, bank, 2e-3);
  EXPECT_NEAR(euler_from_quaternion(traj->at(100.0).q_b_n).roll_rad, 0.0, 2e-3);
  EXPECT_NEAR(euler_from_quaternion(traj->at(103.0).q_b_n).roll_rad, -bank, 2e-3);
  // The blended quantity is the turn rate, so tan(roll) follows the quintic: the peak roll
  // rate (at zero roll) is 1.875 * 2 * tan(bank) / 4 s.
  const double peak_rate = 1.875 * 2.0 * std::tan(bank) / 4.0;
  double max_step = 0.0;
  double prev = euler_from_quaternion(traj->at(97.0).q_b_n).roll_rad;
  for (double t = 97.05; t < 103.0; t += 0.05) {
    const double roll = euler_from_quaternion(traj->at(t).q_b_n).roll_rad;
    max_step = std::max(max_step, std::abs(roll - prev));
    prev = roll;
  }
  EXPECT_LT(max_step, 1.01 * peak_rate * 0.05);
  EXPECT_NEAR(std::abs(traj->at(100.0).w_nb_b_radps.x()), peak_rate, 2e-3);
  // Body rate and its derivative stay consistent with the attitude inside the blend.
  for (double t : {98.5, 99.3, 100.6, 101.7}) {
    const TrajectoryState s = traj->at(t);
    const double h = 1e-3;
    const Eigen::Quaterniond dq = traj->at(t - h).q_b_n.conjugate() * traj->at(t + h).q_b_n;
    EXPECT_LE((rotation_vector_from_quaternion(dq) / (2 * h) - s.w_nb_b_radps).norm(), 1e-6) << t;
    const Eigen::Vector3d dw_fd = derivative([&](double x) { return traj->at(x).w_nb_b_radps; }, t, 1e-2);
    EXPECT_LE((dw_fd - s.dw_nb_b_radps2).norm(), 1e-5 + 1e-4 * s.dw_nb_b_radps2.norm()) << t;
  }
}

TEST(TrajectoryPresets, WingRockRollsTwentyDegrees) {
  const auto traj = make_preset_trajectory("air-wingrock", kStart, 1.0, 200.0);
  double max_roll = 0.0, min_roll = 0.0;
  for (double t = 0.0; t < 20.0; t += 0.05) {
    const EulerAngles e = euler_from_quaternion(traj->at(t).q_b_n);
    max_roll = std::max(max_roll, e.roll_rad);
    min_roll = std::min(min_roll, e.roll_rad);
  }
  EXPECT_NEAR(max_roll * 180 / kPi, 20.0, 0.05);
  EXPECT_NEAR(min_roll * 180 / kPi, -20.0, 0.05);
}

TEST(TrajectoryPresets, SpiralClimbsAndAccelRunStartsFromRest) {
  const auto spiral = make_preset_trajectory("air-spiral", kStart, 0.0, 200.0);
  EXPECT_NEAR(spiral->at(100.0).v_ned_mps.z(), -0.2, 1e-3);
  const auto accel = make_preset_trajectory("land-accel", kStart, 0.0, 200.0);
  EXPECT_NEAR(accel->at(0.0).v_ned_mps.norm(), 0.0, 1e-12);
  EXPECT_NEAR(accel->at(100.0).v_ned_mps.norm(), 10.0, 1e-6);
  const auto stat = make_preset_trajectory("static", kStart, 0.0, 200.0);
  EXPECT_NEAR((stat->at(123.0).r_ecef_m - wgs84::llh_to_ecef(kStart)).norm(), 0.0, 1e-9);
}

TEST(TrajectoryPresets, UnknownNameListsTheValidOnes) {
  try {
    make_preset_trajectory("land-loop", kStart, 0.0, 10.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("land-circle"), std::string::npos);
  }
}

}  // namespace
}  // namespace deepnav
