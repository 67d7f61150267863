#pragma once
// Shared pieces of the aiding tests: a trajectory with its simulated IMU (lever arm
// between IMU and antenna), truth at any time, and a perturbed starting state.
#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "aiding/aided_navigator.hpp"
#include "ins/frames.hpp"
#include "ins/imu_model.hpp"
#include "ins/sim/imu_simulator.hpp"
#include "ins/sim/trajectory_presets.hpp"

namespace deepnav::aiding::testing {

inline const Eigen::Vector3d kImuFromAntenna_b{0.8, -0.3, 0.4};  ///< IMU position from the antenna, body axes

struct SimulatedRun {
  std::unique_ptr<Trajectory> trajectory;  ///< of the antenna
  std::vector<ImuSample> imu;
  ImuErrorModel imu_model;

  SimulatedRun(const std::string& preset, const std::string& grade, double duration_s, double imu_rate_hz,
               std::uint64_t seed) {
    trajectory =
        make_preset_trajectory(preset, wgs84::Llh{37.5 * M_PI / 180, 127.0 * M_PI / 180, 50.0}, 0.0, duration_s);
    imu_model = load_imu_grade(std::string(DEEPNAV_SOURCE_DIR) + "/data/imu_grades.yaml", grade).model;
    imu_model.sample_rate_hz = imu_rate_hz;
    ImuSimConfig cfg;
    cfg.imu = imu_model;
    cfg.lever_arm_b_m = kImuFromAntenna_b;
    imu = simulate_imu(*trajectory, cfg, seed);
  }

  /// The IMU's true navigation state at t.
  NavState imu_truth(double t_s) const {
    const TrajectoryState s = trajectory->at(t_s);
    NavState n;
    n.t_s = t_s;
    n.q_b_n = s.q_b_n;
    const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
    n.llh = wgs84::ecef_to_llh(s.r_ecef_m + ned_to_ecef_vector(llh, s.q_b_n * kImuFromAntenna_b));
    n.v_ned_mps = s.v_ned_mps + s.q_b_n * s.w_nb_b_radps.cross(kImuFromAntenna_b);
    return n;
  }

  /// The true state with known errors: metres of position, m/s, and a tilt (rad, NED).
  NavState perturbed_start(const Eigen::Vector3d& dr_ned_m, const Eigen::Vector3d& dv_ned_mps,
                           const Eigen::Vector3d& tilt_rad) const {
    NavState n = imu_truth(0.0);
    const Eigen::Vector3d r = wgs84::llh_to_ecef(n.llh) + ned_to_ecef_vector(n.llh, dr_ned_m);
    n.llh = wgs84::ecef_to_llh(r);
    n.v_ned_mps += dv_ned_mps;
    n.q_b_n = Eigen::Quaterniond(Eigen::AngleAxisd(tilt_rad.norm(), tilt_rad.normalized())) * n.q_b_n;
    return n;
  }
};

inline NavigatorConfig navigator_config(const ImuErrorModel& imu) {
  NavigatorConfig cfg;
  cfg.noise = process_noise_from(imu, OscillatorNoise{});
  cfg.lever_arm_imu_to_antenna_b_m = -kImuFromAntenna_b;
  return cfg;
}

/// Horizontal and vertical error (m) of the navigator's antenna position against truth.
inline Eigen::Vector3d antenna_error_ned(const AidedNavigator& nav, const Trajectory& truth) {
  const TrajectoryState s = truth.at(nav.time_s());
  return ned_offset_m(s.r_ecef_m, nav.antenna_ecef_m());
}

/// Heading error (rad) of the INS against the truth.
inline double heading_error_rad(const AidedNavigator& nav, const Trajectory& truth) {
  const Eigen::Matrix3d C_est = nav.ins().q_b_n.toRotationMatrix();
  const Eigen::Matrix3d C_true = truth.at(nav.time_s()).q_b_n.toRotationMatrix();
  const Eigen::Matrix3d dC = C_est * C_true.transpose();
  return std::atan2(dC(1, 0) - dC(0, 1), dC(0, 0) + dC(1, 1));
}

}  // namespace deepnav::aiding::testing
