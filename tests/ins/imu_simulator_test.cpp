#include "ins/sim/imu_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ins/frames.hpp"
#include "ins_test_trajectories.hpp"

namespace deepnav {
namespace {

const wgs84::Llh kSeoul{37.5 * M_PI / 180.0, 127.0 * M_PI / 180.0, 100.0};

TEST(IdealImu, AtRestSensesGravityAndEarthRate) {
  test::FixedPointTrajectory traj(kSeoul, 10.0);
  const TrajectoryState s = traj.at(0.0);
  const ImuRates r = ideal_imu_rates(s, Eigen::Vector3d::Zero());
  const double g = wgs84::normal_gravity_mps2(kSeoul.lat_rad, kSeoul.height_m);
  EXPECT_NEAR(r.f_b_mps2.norm(), g, 1e-12);
  // f points up (-down in NED) and w is the Earth rate, both seen through the attitude.
  const Eigen::Matrix3d C_b_n = s.q_b_n.toRotationMatrix();
  EXPECT_NEAR((C_b_n * r.f_b_mps2 - Eigen::Vector3d(0, 0, -g)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(r.w_ib_b_radps.norm(), wgs84::kEarthRate_radps, 1e-18);
  const Eigen::Vector3d w_n = C_b_n * r.w_ib_b_radps;
  EXPECT_NEAR(w_n.x(), wgs84::kEarthRate_radps * std::cos(kSeoul.lat_rad), 1e-18);
  EXPECT_NEAR(w_n.y(), 0.0, 1e-18);
  EXPECT_NEAR(w_n.z(), -wgs84::kEarthRate_radps * std::sin(kSeoul.lat_rad), 1e-18);
}

TEST(IdealImu, EastRunSpecificForceMatchesEcefDerivation) {
  // Independent check of the NED formula: f = C_e_b (a_ecef + 2 w_ie x v_ecef) - C_n_b g_n,
  // with a_ecef and v_ecef by central differences of the trajectory's ECEF position.
  test::EastRunTrajectory traj(kSeoul, 140.0, 100.0);
  const double t = 50.0, h = 0.5;
  const Eigen::Vector3d r0 = traj.at(t - h).r_ecef_m, r1 = traj.at(t).r_ecef_m, r2 = traj.at(t + h).r_ecef_m;
  const Eigen::Vector3d v_e = (r2 - r0) / (2 * h);
  const Eigen::Vector3d a_e = (r2 - 2 * r1 + r0) / (h * h);
  const Eigen::Vector3d w_ie_e(0, 0, wgs84::kEarthRate_radps);
  const TrajectoryState s = traj.at(t);
  const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
  const Eigen::Vector3d g_n(0, 0, wgs84::normal_gravity_mps2(llh.lat_rad, llh.height_m));
  const Eigen::Matrix3d C_n_b = s.q_b_n.conjugate().toRotationMatrix();
  const Eigen::Vector3d f_expected = C_n_b * (C_e_n(llh.lat_rad, llh.lon_rad) * (a_e + 2 * w_ie_e.cross(v_e)) - g_n);
  const ImuRates r = ideal_imu_rates(s, Eigen::Vector3d::Zero());
  // Central differences of a 6400 km position: round-off ~1e-8 m/s^2 at h = 0.5 s.
  EXPECT_NEAR((r.f_b_mps2 - f_expected).norm(), 0.0, 1e-6);
  // The centripetal part (v^2/R ~ 3 mm/s^2) is resolved, not lost in that tolerance.
  const Eigen::Vector3d f_without_motion = C_n_b * (-g_n);
  EXPECT_GT((r.f_b_mps2 - f_without_motion).norm(), 1e-3);
}

TEST(IdealImu, IncrementsIntegrateTheRatesWithinTheInterval) {
  test::ConingTrajectory traj(kSeoul, 10.0, 0.1, 2.0);
  const double t0 = 3.0, t1 = 3.01;
  const ImuSample inc = ideal_imu_increment(traj, t0, t1, Eigen::Vector3d(0.3, -0.2, 0.5));
  // Reference: midpoint rule with 20000 sub-steps.
  Eigen::Vector3d dth = Eigen::Vector3d::Zero(), dv = dth;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + (i + 0.5) * (t1 - t0) / n;
    const ImuRates r = ideal_imu_rates(traj.at(t), Eigen::Vector3d(0.3, -0.2, 0.5));
    dth += r.w_ib_b_radps * (t1 - t0) / n;
    dv += r.f_b_mps2 * (t1 - t0) / n;
  }
  EXPECT_NEAR((inc.dtheta_b_rad - dth).norm(), 0.0, 1e-12);
  EXPECT_NEAR((inc.dv_b_mps - dv).norm(), 0.0, 1e-10);
  EXPECT_DOUBLE_EQ(inc.t_s, t1);
  // Rate x dt at the interval's end would be visibly wrong for this motion.
  const ImuRates end = ideal_imu_rates(traj.at(t1), Eigen::Vector3d::Zero());
  EXPECT_GT((end.w_ib_b_radps * 0.01 - inc.dtheta_b_rad).norm(), 1e-5);
}

class SpinTrajectory : public test::FixedPointTrajectory {
 public:
  using FixedPointTrajectory::FixedPointTrajectory;
  EulerKinematics attitude(double t) const override {
    EulerKinematics k;
    k.angles = {0.0, 0.0, 2.0 * t};
    k.rate_radps = {0.0, 0.0, 2.0};
    return k;
  }
};

TEST(IdealImu, LeverArmAddsCentripetalAcceleration) {
  SpinTrajectory traj(kSeoul, 10.0);
  const Eigen::Vector3d l(0.5, 0.0, 0.0);
  const TrajectoryState s = traj.at(1.0);
  const ImuRates at_ref = ideal_imu_rates(s, Eigen::Vector3d::Zero());
  const ImuRates at_imu = ideal_imu_rates(s, l);
  EXPECT_EQ(at_ref.w_ib_b_radps, at_imu.w_ib_b_radps);
  // Yaw rate 2 rad/s at 0.5 m: 2 m/s^2 towards the spin axis (-x).
  const Eigen::Vector3d diff = at_imu.f_b_mps2 - at_ref.f_b_mps2;
  EXPECT_NEAR(diff.x(), -2.0, 1e-3);
  EXPECT_NEAR(diff.y(), 0.0, 1e-3);
}

TEST(ImuSimulator, SampleTimesComeFromTheCounter) {
  test::FixedPointTrajectory traj(kSeoul, 2.0);
  ImuSimConfig cfg;
  cfg.imu.sample_rate_hz = 100.0;
  const auto samples = simulate_imu(traj, cfg, 1);
  ASSERT_EQ(samples.size(), 200u);
  EXPECT_DOUBLE_EQ(samples.front().t_s, 0.01);
  EXPECT_DOUBLE_EQ(samples[149].t_s, 1.5);
  EXPECT_DOUBLE_EQ(samples.back().t_s, 2.0);
  // At rest the increments are rate x dt.
  const ImuRates r = ideal_imu_rates(traj.at(0.0), Eigen::Vector3d::Zero());
  EXPECT_NEAR((samples[7].dv_b_mps - r.f_b_mps2 * 0.01).norm(), 0.0, 1e-14);
  EXPECT_NEAR((samples[7].dtheta_b_rad - r.w_ib_b_radps * 0.01).norm(), 0.0, 1e-19);
}

TEST(ImuSimulator, AppliesTheErrorModelReproducibly) {
  test::FixedPointTrajectory traj(kSeoul, 1.0);
  ImuSimConfig ideal;
  ImuSimConfig noisy;
  noisy.imu.accel.bias = Eigen::Vector3d(1e-3, 0, 0);
  noisy.imu.gyro.random_walk = 1e-4;
  const auto a = simulate_imu(traj, ideal, 5);
  const auto b = simulate_imu(traj, noisy, 5);
  const auto c = simulate_imu(traj, noisy, 5);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(b[k].dv_b_mps.x() - a[k].dv_b_mps.x(), 1e-5, 1e-15);
    EXPECT_EQ(b[k].dtheta_b_rad, c[k].dtheta_b_rad);
  }
  EXPECT_GT((b[3].dtheta_b_rad - a[3].dtheta_b_rad).norm(), 0.0);
}

TEST(ImuSimulator, RejectsBadRate) {
  test::FixedPointTrajectory traj(kSeoul, 1.0);
  ImuSimConfig cfg;
  cfg.imu.sample_rate_hz = 0.0;
  EXPECT_THROW(ImuSimulator(traj, cfg, 1), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
