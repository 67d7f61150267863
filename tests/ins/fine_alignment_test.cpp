#include "ins/fine_alignment.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "ins/coarse_alignment.hpp"
#include "ins/sim/static_imu_sim.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kDegPerHour = kDeg / 3600.0;
constexpr double kMilliG = 9.80665e-3;
const double kLat = 35.0 * kDeg;
const double kGravity = wgs84::normal_gravity_mps2(kLat, 0.0);

Eigen::Matrix3d dcm(double roll_deg, double pitch_deg, double yaw_deg) {
  return (Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

struct AlignmentCase {
  Eigen::Matrix3d C_true;
  StaticImuErrors errors;
  FineAlignmentConfig config;
};

// Tactical grade: 1 deg/h gyro bias, 0.1 deg/sqrt(h) ARW, 1 mg accelerometer bias,
// 50 ug/sqrt(Hz) VRW (scale sets the biases and noises together: 0.01 is navigation grade).
AlignmentCase make_case(double yaw_deg, double scale) {
  AlignmentCase s;
  s.C_true = dcm(2.0, -1.0, yaw_deg);
  s.errors.gyro_bias_b_radps = Eigen::Vector3d(1.0, -1.0, 1.0) * kDegPerHour * scale;
  s.errors.accel_bias_b_mps2 = Eigen::Vector3d(1.0, -1.0, 1.0) * kMilliG * scale;
  s.errors.gyro_noise_density_radps_per_rthz = 0.1 * kDeg / 60.0 * scale;
  s.errors.accel_noise_density_mps2_per_rthz = 50e-6 * 9.80665 * scale;
  s.config.lat_rad = kLat;
  s.config.gravity_mps2 = kGravity;
  s.config.gyro_noise_density_radps_per_rthz = s.errors.gyro_noise_density_radps_per_rthz;
  s.config.accel_noise_density_mps2_per_rthz = s.errors.accel_noise_density_mps2_per_rthz;
  s.config.gyro_bias_sigma_radps = 1.0 * kDegPerHour * scale;
  s.config.accel_bias_sigma_mps2 = 1.0 * kMilliG * scale;
  s.config.initial_tilt_sigma_rad = 0.2 * kDeg;
  s.config.initial_heading_sigma_rad = 20.0 * kDeg;
  return s;
}

Eigen::Matrix3d coarse_from(const std::vector<ImuReading>& imu, std::size_t n, const AlignmentCase& s) {
  std::vector<Eigen::Vector3d> f, w;
  for (std::size_t i = 0; i < n; ++i) {
    f.push_back(imu[i].f_b_mps2);
    w.push_back(imu[i].w_ib_b_radps);
  }
  StationarityLimits lim;
  lim.accel_noise_mps2 = s.errors.accel_noise_density_mps2_per_rthz * 10.0;  // 100 Hz
  lim.gyro_noise_radps = s.errors.gyro_noise_density_radps_per_rthz * 10.0;
  const auto coarse = coarse_align(f, w, kLat, kGravity, CoarseAlignmentMethod::kTwoStep, lim);
  if (!coarse.attitude) throw std::runtime_error(coarse.stationarity.reason);
  return coarse.attitude->C_b_n;
}

TEST(FineAlignment, HeadingLimitFormula) {
  // 1 deg/h east gyro error at 35 deg: 1 / (15.041 * cos 35) rad = 4.65 deg.
  EXPECT_NEAR(std::abs(gyrocompass_heading_limit_rad(1.0 * kDegPerHour, kLat)) / kDeg, 4.65, 0.01);
}

TEST(FineAlignment, TacticalHeadingSettlesAtTheGyroBiasLimit) {
  for (double yaw : {0.0, 123.0, 270.0}) {
    const AlignmentCase s = make_case(yaw, 1.0);
    std::mt19937_64 rng(11);
    const auto imu = simulate_static_imu(s.C_true, kLat, kGravity, s.errors, 900.0, 100.0, rng);
    const Eigen::Vector3d limit = two_step_tilt_error_rad(s.C_true * s.errors.accel_bias_b_mps2,
                                                          s.C_true * s.errors.gyro_bias_b_radps, kLat, kGravity);
    const auto trace = run_fine_alignment(imu, s.config, coarse_from(imu, 1000, s), s.C_true, 10.0);
    // ARW alone leaves ~1 deg (1 sigma) of heading noise after 900 s at 0.1 deg/sqrt(h).
    EXPECT_NEAR(trace.tilt_error_rad.back().z(), limit.z(), 2.5 * kDeg) << "yaw " << yaw;
    // The filter knows it cannot beat the limit: its heading sigma floors near 4.6 deg.
    EXPECT_NEAR(trace.attitude_sigma_rad.back().z() / kDeg, 4.6, 0.3);
    // Levels at the accelerometer limit (-df_E/g, df_N/g; 1 mg ~ 0.06 deg), which the
    // filter also knows it cannot beat (its level sigma stays near the 1 mg prior).
    EXPECT_LT((trace.tilt_error_rad.back().head<2>() - limit.head<2>()).norm(), 0.02 * kDeg) << "yaw " << yaw;
    EXPECT_NEAR(trace.attitude_sigma_rad.back().x() / kDeg, 0.055, 0.01);
  }
}

TEST(FineAlignment, NavigationGradeHeadingConvergesTightly) {
  const AlignmentCase s = make_case(200.0, 0.01);
  std::mt19937_64 rng(3);
  const auto imu = simulate_static_imu(s.C_true, kLat, kGravity, s.errors, 600.0, 100.0, rng);
  const Eigen::Vector3d limit = two_step_tilt_error_rad(s.C_true * s.errors.accel_bias_b_mps2,
                                                        s.C_true * s.errors.gyro_bias_b_radps, kLat, kGravity);
  const Eigen::Matrix3d coarse = coarse_from(imu, 1000, s);
  const auto trace = run_fine_alignment(imu, s.config, coarse, s.C_true, 5.0);
  EXPECT_GT(std::abs(tilt_error_ned_rad(coarse, s.C_true).z() - limit.z()), 0.1 * kDeg);  // coarse is not there yet
  EXPECT_NEAR(trace.tilt_error_rad.back().z(), limit.z(), 0.05 * kDeg);
  EXPECT_LT(heading_settling_time_s(trace, limit.z(), 0.1 * kDeg), 400.0);
}

TEST(FineAlignment, BadInputIsRejected) {
  FineAlignmentConfig config;
  config.zupt_interval_s = 0.0;
  EXPECT_THROW(FineAlignment(config, Eigen::Matrix3d::Identity()), std::invalid_argument);
  FineAlignment ok(FineAlignmentConfig{}, Eigen::Matrix3d::Identity());
  ImuReading bad;
  bad.f_b_mps2.x() = std::nan("");
  EXPECT_THROW(ok.step(bad, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
