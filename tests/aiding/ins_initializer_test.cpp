// The moving INS start at a fix rate above 1 Hz: a receiver giving 4 fixes a second (the
// walk_0827 recording's u-blox) must still difference velocities about a second apart,
// or the specific force from the fixes carries four times the noise into the tilt.
#include "aiding/ins_initializer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ins/frames.hpp"
#include "ins/imu_model.hpp"
#include "ins/rotations.hpp"
#include "ins/wgs84.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct StartOutcome {
  bool started = false;
  double t_s = 0.0;
  EulerAngles attitude{};
};

/// Level walk north at 1.5 m/s (body x forward): IMU at 100 Hz measuring gravity only,
/// fixes at `fix_rate_hz` whose velocities carry `velocity_noise_mps` per axis.
StartOutcome walk_north(double fix_rate_hz, double velocity_noise_mps, std::uint64_t seed) {
  ImuErrorModel imu;  // a perfect IMU: the test is about the GNSS side
  InsInitializer init(imu, Eigen::Vector3d::Zero());
  const wgs84::Llh llh{40.0 * kDeg, -105.0 * kDeg, 1600.0};
  const double g = wgs84::normal_gravity_mps2(llh.lat_rad, llh.height_m);
  const Eigen::Vector3d v_ned(1.5, 0.0, 0.0);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, velocity_noise_mps);
  const int imu_per_fix = static_cast<int>(std::lround(100.0 / fix_rate_hz));
  for (int k = 1; k <= 100 * 10; ++k) {
    ImuSample s;
    s.t_s = 0.01 * k;
    s.dv_b_mps = Eigen::Vector3d(0.0, 0.0, -g) * 0.01;
    init.add_imu(s);
    if (k % imu_per_fix != 0) continue;
    GnssFix fix;
    fix.t_s = s.t_s;
    fix.r_antenna_ecef_m = wgs84::llh_to_ecef(llh) + ned_to_ecef_vector(llh, v_ned * s.t_s);
    fix.v_antenna_ecef_mps = ned_to_ecef_vector(llh, v_ned + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    if (const std::optional<InsStart> start = init.add_fix(fix)) {
      return {true, fix.t_s, euler_from_quaternion(start->state.q_b_n)};
    }
  }
  return {};
}

TEST(InsInitializer, MovingStartAtFourFixesASecondDifferencesASecondApart) {
  // 5 cm/s per fix: 0.25 s differences would make 0.28 m/s^2 of horizontal specific-force
  // noise, 1.6 deg of tilt; one-second differences 0.07 m/s^2, 0.4 deg.
  double worst_tilt = 0.0, worst_heading = 0.0, latest = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const StartOutcome s = walk_north(4.0, 0.05, seed);
    ASSERT_TRUE(s.started) << "seed " << seed;
    latest = std::max(latest, s.t_s);
    worst_tilt = std::max({worst_tilt, std::abs(s.attitude.roll_rad), std::abs(s.attitude.pitch_rad)});
    worst_heading = std::max(worst_heading, std::abs(std::remainder(s.attitude.yaw_rad, 2.0 * M_PI)));
  }
  EXPECT_GE(latest, 1.0);  // never before a second of fixes
  EXPECT_LE(latest, 2.0);  // and soon after
  EXPECT_LT(worst_tilt, 1.2 * kDeg);
  // Heading is the current fix's direction of travel: 0.05 / 1.5 rad (1.9 deg) of noise, the
  // start's 5 deg sigma covers it.
  EXPECT_LT(worst_heading, 6.0 * kDeg);
}

TEST(InsInitializer, MovingStartAtOneFixASecondIsUnchanged) {
  const StartOutcome s = walk_north(1.0, 0.05, 3);
  ASSERT_TRUE(s.started);
  EXPECT_DOUBLE_EQ(s.t_s, 2.0);  // the second fix, a second after the first
  EXPECT_LT(std::abs(s.attitude.roll_rad), 1.2 * kDeg);
  EXPECT_LT(std::abs(s.attitude.pitch_rad), 1.2 * kDeg);
}

}  // namespace
}  // namespace deepnav::aiding
