#include "ins/strapdown.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <memory>

#include "ins/frames.hpp"
#include "ins/rotations.hpp"
#include "ins/sim/imu_simulator.hpp"
#include "ins_test_trajectories.hpp"

#include "ins/sim/trajectory_presets.hpp"

namespace deepnav {
namespace {

const wgs84::Llh kStart{35.0 * M_PI / 180.0, 127.0 * M_PI / 180.0, 200.0};

NavState truth_nav_state(const Trajectory& traj, double t_s) {
  const TrajectoryState s = traj.at(t_s);
  NavState n;
  n.t_s = t_s;
  n.llh = wgs84::ecef_to_llh(s.r_ecef_m);
  n.v_ned_mps = s.v_ned_mps;
  n.q_b_n = s.q_b_n;
  return n;
}

struct RunErrors {
  double position_m;
  double velocity_mps;
  double attitude_deg;
};

RunErrors errors_against_truth(const NavState& est, const Trajectory& traj) {
  const TrajectoryState truth = traj.at(est.t_s);
  RunErrors e;
  e.position_m = (wgs84::llh_to_ecef(est.llh) - truth.r_ecef_m).norm();
  e.velocity_mps = (est.v_ned_mps - truth.v_ned_mps).norm();
  e.attitude_deg = rotation_vector_from_quaternion(est.q_b_n * truth.q_b_n.conjugate()).norm() * 180.0 / M_PI;
  return e;
}

RunErrors mechanize_ideal(const Trajectory& traj, double rate_hz) {
  ImuSimConfig cfg;
  cfg.imu.sample_rate_hz = rate_hz;
  ImuSimulator sim(traj, cfg, 1);
  StrapdownNed ins(truth_nav_state(traj, 0.0));
  while (!sim.done()) ins.update(sim.next());
  return errors_against_truth(ins.state(), traj);
}

TEST(Strapdown, StaticHourWithPerfectSensorsStaysPut) {
  test::FixedPointTrajectory traj(kStart, 3600.0);
  const RunErrors e = mechanize_ideal(traj, 100.0);
  // Only round-off drives the errors (the vertical channel would amplify any
  // inconsistency between simulator and mechanization gravity by ~e^6 in an hour).
  EXPECT_LT(e.position_m, 1e-3);
  EXPECT_LT(e.velocity_mps, 1e-5);
  EXPECT_LT(e.attitude_deg, 1e-7);
}

TEST(Strapdown, EastRunAt500KmhFollowsTheParallel) {
  // Constant velocity over the curved Earth: transport rate and Coriolis at work.
  test::EastRunTrajectory traj(kStart, 500.0 / 3.6, 200.0);
  const RunErrors e = mechanize_ideal(traj, 100.0);
  EXPECT_LT(e.position_m, 0.01);
  EXPECT_LT(e.velocity_mps, 1e-4);
  EXPECT_LT(e.attitude_deg, 1e-6);
}

TEST(Strapdown, ConingMotionAtRestKeepsAttitude) {
  // 0.05 rad coning at 2 Hz, sampled at 100 Hz for 200 s.
  test::ConingTrajectory traj(kStart, 200.0, 0.05, 2.0);
  const RunErrors e = mechanize_ideal(traj, 100.0);
  // Residuals of the two-sample coning and third-order rotation compensation terms
  // (both fall with the 4th power of the interval): 0.0015 deg and 6 mm here.
  EXPECT_LT(e.attitude_deg, 0.003);
  EXPECT_LT(e.position_m, 0.05);
}

TEST(Strapdown, LeverArmImuFollowsItsOwnMountingPoint) {
  // The IMU 1 m ahead and 0.5 m above the reference point of a coning body: the
  // mechanized position is the IMU's, reference point + C_b_n l.
  test::ConingTrajectory traj(kStart, 60.0, 0.1, 0.5);
  const Eigen::Vector3d l(1.0, 0.0, -0.5);
  ImuSimConfig cfg;
  cfg.lever_arm_b_m = l;
  const auto at_imu = [&](double t) {
    const TrajectoryState s = traj.at(t);
    NavState n = truth_nav_state(traj, t);
    const Eigen::Vector3d offset_ned = s.q_b_n * l;
    n.llh = wgs84::ecef_to_llh(s.r_ecef_m + C_n_e(n.llh.lat_rad, n.llh.lon_rad) * offset_ned);
    n.v_ned_mps = s.q_b_n * s.w_nb_b_radps.cross(l);
    return n;
  };
  ImuSimulator sim(traj, cfg, 1);
  StrapdownNed ins(at_imu(0.0));
  while (!sim.done()) ins.update(sim.next());
  const NavState truth = at_imu(ins.state().t_s);
  EXPECT_LT((wgs84::llh_to_ecef(ins.state().llh) - wgs84::llh_to_ecef(truth.llh)).norm(), 0.05);
  EXPECT_LT((ins.state().v_ned_mps - truth.v_ned_mps).norm(), 0.005);
}

TEST(Strapdown, Paper003AircraftCircleEndsWithinOneMetreAndHundredthDegree) {
  // The acceptance test: 500 km/h circle of radius 4422 m, error-free IMU at
  // 100 Hz, 200 s, INS started from the true state.
  const auto traj = make_preset_trajectory("air-circle", kStart, 0.0, 200.0);
  const RunErrors e = mechanize_ideal(*traj, 100.0);
  RecordProperty("position_error_m", std::to_string(e.position_m));
  RecordProperty("attitude_error_deg", std::to_string(e.attitude_deg));
  EXPECT_LT(e.position_m, 1.0);
  std::printf("air circle, 200 s at 100 Hz: position error %.3e m, attitude error %.3e deg\n", e.position_m,
              e.attitude_deg);
  EXPECT_LT(e.attitude_deg, 0.01);
}

TEST(StrapdownFeedback, PositionVelocityAttitudeCorrections) {
  NavState s0;
  s0.llh = kStart;
  s0.q_b_n = quaternion_from_euler({0.1, 0.05, 1.0});
  StrapdownNed ins(s0);
  const Eigen::Vector3d r0 = wgs84::llh_to_ecef(ins.state().llh);
  ins.correct_position({10.0, -20.0, 5.0});
  const Eigen::Vector3d moved_ned = C_e_n(kStart.lat_rad, kStart.lon_rad) * (wgs84::llh_to_ecef(ins.state().llh) - r0);
  EXPECT_NEAR((moved_ned - Eigen::Vector3d(10.0, -20.0, 5.0)).norm(), 0.0, 1e-3);

  ins.correct_velocity({0.5, -0.25, 0.125});
  EXPECT_EQ(ins.state().v_ned_mps, Eigen::Vector3d(0.5, -0.25, 0.125));

  // A rotation about NED down changes the yaw only.
  ins.correct_attitude({0.0, 0.0, 0.01});
  const EulerAngles e = euler_from_quaternion(ins.state().q_b_n);
  EXPECT_NEAR(e.yaw_rad, 1.01, 1e-12);
  EXPECT_NEAR(e.roll_rad, 0.1, 1e-12);
  EXPECT_NEAR(e.pitch_rad, 0.05, 1e-12);
  // The correction undoes a tilt error defined as C_est = (I + [eps x]) C_true.
  const Eigen::Vector3d eps(1e-3, -2e-3, 3e-3);
  const Eigen::Quaterniond q_true = ins.state().q_b_n;
  NavState tilted = ins.state();
  tilted.q_b_n = quaternion_from_rotation_vector(eps) * q_true;
  ins.reset(tilted);
  ins.correct_attitude(-eps);
  EXPECT_LT(rotation_vector_from_quaternion(ins.state().q_b_n * q_true.conjugate()).norm(), 1e-12);
}

TEST(StrapdownFeedback, BiasCompensationRemovesAKnownBias) {
  test::FixedPointTrajectory traj(kStart, 60.0);
  ImuSimConfig biased;
  biased.imu.accel.bias = Eigen::Vector3d(2e-3, -1e-3, 3e-3);
  biased.imu.gyro.bias = Eigen::Vector3d(1e-5, 2e-5, -1e-5);
  const auto samples = simulate_imu(traj, biased, 1);
  StrapdownNed raw(truth_nav_state(traj, 0.0)), compensated(truth_nav_state(traj, 0.0));
  compensated.set_bias_compensation(biased.imu.accel.bias, biased.imu.gyro.bias);
  EXPECT_EQ(compensated.accel_bias_compensation_mps2(), biased.imu.accel.bias);
  for (const auto& s : samples) {
    raw.update(s);
    compensated.update(s);
  }
  EXPECT_LT(errors_against_truth(compensated.state(), traj).position_m, 1e-4);
  EXPECT_GT(errors_against_truth(raw.state(), traj).position_m, 1.0);
}

TEST(StrapdownInput, RejectsTimeThatDoesNotAdvanceAndNonFiniteData) {
  NavState s0;
  s0.llh = kStart;
  s0.t_s = 10.0;
  StrapdownNed ins(s0);
  ImuSample s;
  s.t_s = 10.0;
  EXPECT_THROW(ins.update(s), std::invalid_argument);
  s.t_s = 10.01;
  s.dv_b_mps.x() = std::nan("");
  try {
    ins.update(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("10.01"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ins.state().t_s, 10.0);  // rejected samples leave the state alone
}

}  // namespace
}  // namespace deepnav
