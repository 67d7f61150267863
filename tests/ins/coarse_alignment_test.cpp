#include "ins/coarse_alignment.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kDegPerHour = kDeg / 3600.0;
constexpr double kMicroG = 9.80665e-6;
const double kLat = 35.0 * kDeg;
const double kGravity = wgs84::normal_gravity_mps2(kLat, 0.0);

Eigen::Matrix3d dcm(double roll_deg, double pitch_deg, double yaw_deg) {
  return (Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

double angle_diff(double a, double b) { return std::remainder(a - b, 2.0 * std::numbers::pi); }

TEST(CoarseAlignment, PerfectSensorsAreExactAtAnyHeading) {
  for (double yaw_deg : {0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0, 359.0}) {
    for (auto [roll_deg, pitch_deg] : {std::pair{0.0, 0.0}, std::pair{5.0, -5.0}, std::pair{-40.0, 25.0}}) {
      const Eigen::Matrix3d C = dcm(roll_deg, pitch_deg, yaw_deg);
      const StaticImuMean imu = stationary_imu_outputs(C, kLat, kGravity);
      const AlignedAttitude two = align_two_step(imu.f_b_mps2, imu.w_ib_b_radps);
      const AlignedAttitude one = align_one_shot(imu.f_b_mps2, imu.w_ib_b_radps, kLat, kGravity).attitude;
      for (const AlignedAttitude& a : {two, one}) {
        EXPECT_NEAR(angle_diff(a.roll_rad, roll_deg * kDeg), 0.0, 1e-9) << yaw_deg;
        EXPECT_NEAR(angle_diff(a.pitch_rad, pitch_deg * kDeg), 0.0, 1e-9) << yaw_deg;
        EXPECT_NEAR(angle_diff(a.yaw_rad, yaw_deg * kDeg), 0.0, 1e-9) << yaw_deg;
        EXPECT_GE(a.yaw_rad, 0.0);
        EXPECT_LT(a.yaw_rad, 2.0 * std::numbers::pi);
        EXPECT_LT((a.C_b_n - C).norm(), 1e-9);
      }
    }
  }
}

// One body-axis error at a time, at the paper's near-level attitude: the simulated tilt
// must match the analytic first-order formulas within 5 %.
TEST(CoarseAlignment, TiltErrorsMatchAnalyticFormulas) {
  const Eigen::Matrix3d C = dcm(5.0, 5.0, 5.0);
  const StaticImuMean imu = stationary_imu_outputs(C, kLat, kGravity);
  for (int axis = 0; axis < 6; ++axis) {
    Eigen::Vector3d df_b = Eigen::Vector3d::Zero();
    Eigen::Vector3d dw_b = Eigen::Vector3d::Zero();
    if (axis < 3) df_b[axis] = 100.0 * kMicroG;
    else dw_b[axis - 3] = 0.1 * kDegPerHour;
    const Eigen::Vector3d f = imu.f_b_mps2 + df_b;
    const Eigen::Vector3d w = imu.w_ib_b_radps + dw_b;
    const Eigen::Vector3d df_n = C * df_b;
    const Eigen::Vector3d dw_n = C * dw_b;

    const Eigen::Vector3d sim_two = tilt_error_ned_rad(align_two_step(f, w).C_b_n, C);
    const Eigen::Vector3d ana_two = two_step_tilt_error_rad(df_n, dw_n, kLat, kGravity);
    const Eigen::Vector3d sim_one = tilt_error_ned_rad(align_one_shot(f, w, kLat, kGravity).attitude.C_b_n, C);
    const Eigen::Vector3d ana_one = one_shot_tilt_error_rad(df_n, dw_n, kLat, kGravity);
    for (int k = 0; k < 3; ++k) {
      // 5 % of the component, or 1 % of the largest component for ones near zero.
      EXPECT_NEAR(sim_two[k], ana_two[k], std::max(0.05 * std::abs(ana_two[k]), 0.01 * ana_two.norm()))
          << "two-step axis " << axis << " component " << k;
      EXPECT_NEAR(sim_one[k], ana_one[k], std::max(0.05 * std::abs(ana_one[k]), 0.01 * ana_one.norm()))
          << "one-shot axis " << axis << " component " << k;
    }
  }
}

TEST(CoarseAlignment, TwoStepEastTiltCarriesNoGyroError) {
  const Eigen::Matrix3d C = dcm(3.0, -4.0, 210.0);
  const StaticImuMean imu = stationary_imu_outputs(C, kLat, kGravity);
  const Eigen::Vector3d dw_b(0.7, -1.0, 1.0);
  const Eigen::Vector3d w = imu.w_ib_b_radps + dw_b * kDegPerHour;
  const Eigen::Vector3d sim_two = tilt_error_ned_rad(align_two_step(imu.f_b_mps2, w).C_b_n, C);
  EXPECT_LT(std::abs(sim_two.x()), 1e-12);
  EXPECT_LT(std::abs(sim_two.y()), 1e-12);
  EXPECT_GT(std::abs(sim_two.z()), 1e-3);  // the gyro error all goes into heading
  const Eigen::Vector3d sim_one = tilt_error_ned_rad(align_one_shot(imu.f_b_mps2, w, kLat, kGravity).attitude.C_b_n, C);
  EXPECT_GT(std::abs(sim_one.y()), 1e-3);  // the one-shot east tilt does depend on the gyros
}

TEST(CoarseAlignment, OneShotPitchErrorReachesPaperOrderForZGyro) {
  const Eigen::Matrix3d C = dcm(0.0, 0.0, 0.0);
  const StaticImuMean imu = stationary_imu_outputs(C, kLat, kGravity);
  const Eigen::Vector3d w = imu.w_ib_b_radps + Eigen::Vector3d(0.0, 0.0, 1.0 * kDegPerHour);
  const AlignedAttitude one = align_one_shot(imu.f_b_mps2, w, kLat, kGravity).attitude;
  // Paper 000 [docs/references.md]: about 2.3 deg. 1/2 * (1 deg/h) / (15.04 deg/h * cos 35 deg) = 2.33 deg.
  EXPECT_NEAR(std::abs(one.pitch_rad) / kDeg, 2.33, 0.1);
  const AlignedAttitude two = align_two_step(imu.f_b_mps2, w);
  EXPECT_LT(std::abs(two.pitch_rad), 1e-12);
}

struct Samples {
  std::vector<Eigen::Vector3d> f, w;
};

Samples rest_samples(const Eigen::Matrix3d& C, int n, double accel_noise, double gyro_noise, std::mt19937_64& rng) {
  const StaticImuMean imu = stationary_imu_outputs(C, kLat, kGravity);
  std::normal_distribution<double> unit;
  Samples s;
  for (int i = 0; i < n; ++i) {
    s.f.push_back(imu.f_b_mps2 + accel_noise * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    s.w.push_back(imu.w_ib_b_radps + gyro_noise * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
  }
  return s;
}

TEST(CoarseAlignment, RestDataIsAlignedAndMovingDataIsRefused) {
  std::mt19937_64 rng(42);
  StationarityLimits limits;
  limits.accel_noise_mps2 = 1e-3;
  limits.gyro_noise_radps = 1e-5;
  const Eigen::Matrix3d C = dcm(2.0, 1.0, 123.0);
  Samples rest = rest_samples(C, 2000, limits.accel_noise_mps2, limits.gyro_noise_radps, rng);
  const CoarseAlignmentOutcome ok =
      coarse_align(rest.f, rest.w, kLat, kGravity, CoarseAlignmentMethod::kTwoStep, limits);
  ASSERT_TRUE(ok.stationarity.stationary) << ok.stationarity.reason;
  ASSERT_TRUE(ok.attitude.has_value());
  EXPECT_NEAR(angle_diff(ok.attitude->yaw_rad, 123.0 * kDeg), 0.0, 3.0 * kDeg);

  // Turning at 1 deg/s: smooth (no extra noise) but far above Earth rate.
  Samples turning = rest;
  for (auto& w : turning.w) w.z() += 1.0 * kDeg;
  const CoarseAlignmentOutcome turn =
      coarse_align(turning.f, turning.w, kLat, kGravity, CoarseAlignmentMethod::kOneShot, limits);
  EXPECT_FALSE(turn.stationarity.stationary);
  EXPECT_FALSE(turn.attitude.has_value());
  EXPECT_NE(turn.stationarity.reason.find("angular rate"), std::string::npos) << turn.stationarity.reason;

  // Accelerating at 2 m/s^2 forward (a smooth acceleration lengthens |f| only at second
  // order: 0.2 m/s^2 here, above the 0.05 m/s^2 allowed for bias and gravity model).
  Samples accelerating = rest;
  for (auto& f : accelerating.f) f.x() += 2.0;
  const CoarseAlignmentOutcome acc =
      coarse_align(accelerating.f, accelerating.w, kLat, kGravity, CoarseAlignmentMethod::kTwoStep, limits);
  EXPECT_FALSE(acc.attitude.has_value());
  EXPECT_NE(acc.stationarity.reason.find("gravity"), std::string::npos) << acc.stationarity.reason;

  // Engine vibration / rocking: zero-mean, but far noisier than the sensor.
  Samples rocking = rest;
  for (std::size_t i = 0; i < rocking.f.size(); ++i) {
    const double s = std::sin(0.3 * static_cast<double>(i));
    rocking.f[i].y() += 0.05 * s;
    rocking.w[i].x() += 2e-3 * s;
  }
  const CoarseAlignmentOutcome rock =
      coarse_align(rocking.f, rocking.w, kLat, kGravity, CoarseAlignmentMethod::kTwoStep, limits);
  EXPECT_FALSE(rock.attitude.has_value());
  EXPECT_NE(rock.stationarity.reason.find("sample std"), std::string::npos) << rock.stationarity.reason;
}

TEST(CoarseAlignment, BadInputIsRejected) {
  std::vector<Eigen::Vector3d> f(10, Eigen::Vector3d(0, 0, -9.8)), w(9, Eigen::Vector3d::Zero());
  EXPECT_THROW(check_stationary(f, w, kGravity, {}), std::invalid_argument);
  w.push_back(Eigen::Vector3d(std::nan(""), 0, 0));
  EXPECT_THROW(check_stationary(f, w, kGravity, {}), std::invalid_argument);
  EXPECT_THROW(align_two_step(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
