#include "aiding/ins_initializer.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <vector>

#include "ins/coarse_alignment.hpp"
#include "ins/frames.hpp"
#include "ins/wgs84.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kRestWindow_s = 5.0;
constexpr double kRestSpeed_mps = 0.2;
constexpr double kMovingSpeed_mps = 1.0;       ///< below this the direction of travel is too noisy for heading
constexpr double kVelocityDifference_s = 1.0;  ///< the moving start's velocity difference spans at least this
constexpr double kFixHistory_s = 3.0;

/// Orthonormal triad of two vectors (first exact, second only in its plane).
Eigen::Matrix3d triad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d t1 = a.normalized();
  const Eigen::Vector3d t2 = a.cross(b).normalized();
  Eigen::Matrix3d m;
  m << t1, t2, t1.cross(t2);
  return m;
}

}  // namespace

InsInitializer::InsInitializer(const ImuErrorModel& imu, const Eigen::Vector3d& lever_arm_imu_to_antenna_b_m)
    : imu_(imu), lever_b_m_(lever_arm_imu_to_antenna_b_m) {}

void InsInitializer::add_imu(const ImuSample& sample) {
  recent_.push_back(sample);
  while (!recent_.empty() && recent_.back().t_s - recent_.front().t_s > kRestWindow_s) recent_.pop_front();
}

std::optional<InsStart> InsInitializer::add_fix(const GnssFix& fix) {
  std::optional<InsStart> start;
  if (recent_.size() >= 2) {
    const wgs84::Llh llh = wgs84::ecef_to_llh(fix.r_antenna_ecef_m);
    const double speed = ecef_to_ned_vector(llh, fix.v_antenna_ecef_mps).norm();
    if (speed < kRestSpeed_mps) start = at_rest(fix);
    if (!start && speed > kMovingSpeed_mps) start = moving(fix);
  }
  fixes_.push_back(fix);
  while (fixes_.size() > 1 && fix.t_s - fixes_.front().t_s > kFixHistory_s) fixes_.pop_front();
  return start;
}

std::optional<InsStart> InsInitializer::at_rest(const GnssFix& fix) const {
  std::vector<Eigen::Vector3d> f, w;
  for (std::size_t k = 1; k < recent_.size(); ++k) {
    const double dt = recent_[k].t_s - recent_[k - 1].t_s;
    f.push_back(recent_[k].dv_b_mps / dt);
    w.push_back(recent_[k].dtheta_b_rad / dt);
  }
  const wgs84::Llh llh = wgs84::ecef_to_llh(fix.r_antenna_ecef_m);
  const double g = wgs84::normal_gravity_mps2(llh.lat_rad, llh.height_m);
  StationarityLimits limits;
  const double dt = (recent_.back().t_s - recent_.front().t_s) / static_cast<double>(recent_.size() - 1);
  limits.accel_noise_mps2 = imu_.accel.random_walk / std::sqrt(dt) + imu_.accel.quantization / dt;
  limits.gyro_noise_radps = imu_.gyro.random_walk / std::sqrt(dt) + imu_.gyro.quantization / dt;
  limits.gyro_bias_radps = std::max(1e-4, 3.0 * (imu_.gyro.bias_sigma + imu_.gyro.bias_instability_sigma));
  const CoarseAlignmentOutcome a = coarse_align(f, w, llh.lat_rad, g, CoarseAlignmentMethod::kTwoStep, limits);
  if (!a.attitude) return std::nullopt;
  InsStart s = finish(fix, a.attitude->C_b_n);
  s.method = "two-step coarse alignment";
  // Levelling is limited by the accelerometer bias, gyrocompassing by the gyro bias
  // against the horizontal Earth rate.
  const double tilt = std::max(1e-4, (imu_.accel.bias_sigma + imu_.accel.bias_instability_sigma) / g);
  const double heading = std::min(0.5, std::max(1e-3, (imu_.gyro.bias_sigma + imu_.gyro.bias_instability_sigma) /
                                                          (wgs84::kEarthRate_radps * std::cos(llh.lat_rad))));
  s.uncertainty.attitude_rad = Eigen::Vector3d(2 * tilt, 2 * tilt, 2 * heading);
  s.uncertainty.velocity_ned_mps = Eigen::Vector3d::Constant(0.1);
  return s;
}

namespace {
// A one-second velocity difference at 0.1 m/s noise: 0.15 m/s^2 and, at 1 g, 0.6 deg.
constexpr double kMaxSpecificForceMismatch_mps2 = 0.5;
constexpr double kMaxTriadAngleMismatch_rad = 2.0 * M_PI / 180.0;
}  // namespace

std::optional<InsStart> InsInitializer::moving(const GnssFix& fix) const {
  // The latest fix at least a second before this one (and not more than two).
  const GnssFix* previous = nullptr;
  for (const GnssFix& f : fixes_)
    if (fix.t_s - f.t_s >= kVelocityDifference_s - 1e-6 && fix.t_s - f.t_s <= 2.0) previous = &f;
  if (previous == nullptr) return std::nullopt;
  const wgs84::Llh llh = wgs84::ecef_to_llh(fix.r_antenna_ecef_m);
  const Eigen::Vector3d v_n = ecef_to_ned_vector(llh, fix.v_antenna_ecef_mps);
  const Eigen::Vector3d a_n =
      ecef_to_ned_vector(llh, fix.v_antenna_ecef_mps - previous->v_antenna_ecef_mps) / (fix.t_s - previous->t_s);
  const double g = wgs84::normal_gravity_mps2(llh.lat_rad, llh.height_m);
  const Eigen::Vector3d f_n = a_n - Eigen::Vector3d(0.0, 0.0, g);
  // Mean specific force over the same interval, in body axes.
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();
  double span = 0.0;
  for (std::size_t k = 1; k < recent_.size(); ++k) {
    if (recent_[k].t_s <= previous->t_s || recent_[k].t_s > fix.t_s + 1e-9) continue;
    dv += recent_[k].dv_b_mps;
    span += recent_[k].t_s - recent_[k - 1].t_s;
  }
  if (span < 0.5 * (fix.t_s - previous->t_s)) return std::nullopt;
  const Eigen::Vector3d f_b = dv / span;
  const Eigen::Vector3d v_b(v_n.norm(), 0.0, 0.0);
  // The two frames must agree on what TRIAD does not fit: the specific force's magnitude
  // and its angle to the direction of travel. A velocity difference spoilt by multipath or
  // a blocked satellite (suburban: metres per second) fails this, and a start from it had
  // pitch wrong by 10 deg in a 60 deg banked turn, which the filter, told 1 deg, never
  // corrected: such a pair of fixes is passed over and the next one tried.
  const auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
  };
  if (std::abs(f_n.norm() - f_b.norm()) > kMaxSpecificForceMismatch_mps2 ||
      std::abs(angle(f_n, v_n) - angle(f_b, v_b)) > kMaxTriadAngleMismatch_rad) {
    spdlog::debug(
        "t = {:.2f} s: moving INS start passed over: specific force {:.2f} m/s^2 from the fixes, {:.2f} from "
        "the IMU; angle to the velocity {:.2f} / {:.2f} deg",
        fix.t_s, f_n.norm(), f_b.norm(), angle(f_n, v_n) * 180.0 / M_PI, angle(f_b, v_b) * 180.0 / M_PI);
    return std::nullopt;
  }
  const Eigen::Matrix3d C_b_n = triad(f_n, v_n) * triad(f_b, v_b).transpose();
  InsStart s = finish(fix, C_b_n);
  s.method = "moving: TRIAD of specific force and direction of travel";
  // Velocity noise over a one-second difference makes a_n uncertain by ~0.1 m/s^2:
  // ~0.6 deg of tilt; sideslip and crab make the heading good to a few degrees.
  s.uncertainty.attitude_rad = Eigen::Vector3d(1.0, 1.0, 5.0) * M_PI / 180.0;
  s.uncertainty.velocity_ned_mps = Eigen::Vector3d::Constant(0.3);
  return s;
}

InsStart InsInitializer::finish(const GnssFix& fix, const Eigen::Matrix3d& C_b_n) const {
  InsStart s;
  const wgs84::Llh llh_ant = wgs84::ecef_to_llh(fix.r_antenna_ecef_m);
  // The IMU is the antenna minus the lever arm; its velocity is the antenna's (the lever
  // arm's rotation term is below the GNSS velocity noise at a start).
  const Eigen::Vector3d r_imu = fix.r_antenna_ecef_m - ned_to_ecef_vector(llh_ant, C_b_n * lever_b_m_);
  s.state.t_s = recent_.back().t_s;
  s.state.llh = wgs84::ecef_to_llh(r_imu);
  s.state.v_ned_mps = ecef_to_ned_vector(llh_ant, fix.v_antenna_ecef_mps);
  s.state.q_b_n = Eigen::Quaterniond(C_b_n).normalized();
  // Position moved to the IMU sample time at the fix's velocity.
  const double dt = s.state.t_s - fix.t_s;
  s.state.llh = wgs84::ecef_to_llh(r_imu + fix.v_antenna_ecef_mps * dt);
  s.uncertainty.position_ned_m = Eigen::Vector3d(fix.horizontal_sigma_m, fix.horizontal_sigma_m, fix.vertical_sigma_m);
  s.uncertainty.accel_bias_mps2 = Eigen::Vector3d::Constant(
      std::max(1e-5, imu_.accel.bias_sigma + imu_.accel.bias_instability_sigma + imu_.accel.bias.norm()));
  s.uncertainty.gyro_bias_radps = Eigen::Vector3d::Constant(
      std::max(1e-8, imu_.gyro.bias_sigma + imu_.gyro.bias_instability_sigma + imu_.gyro.bias.norm()));
  s.uncertainty.clock_bias_m = 10.0;
  s.uncertainty.clock_drift_mps = 0.5;
  return s;
}

}  // namespace deepnav::aiding
