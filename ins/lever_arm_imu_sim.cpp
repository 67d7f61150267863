#include "ins/lever_arm_imu_sim.hpp"
#include "ins/rotations.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace deepnav {
namespace {

Eigen::Vector3d gaussian3(std::normal_distribution<double>& unit, std::mt19937_64& rng) {
  const double x = unit(rng), y = unit(rng), z = unit(rng);
  return {x, y, z};
}

}  // namespace

MemsImuFigures MemsImuFigures::industrial() {
  constexpr double deg = std::numbers::pi / 180.0;
  MemsImuFigures f;
  f.gyro_noise_density_radps_per_rthz = 0.3 * deg / 60.0;  // 0.3 deg/sqrt(h) = 0.005 deg/s/sqrt(Hz)
  f.gyro_drift_sigma_radps = 72.0 * deg / 3600.0;
  f.gyro_drift_tau_s = 300.0;
  f.accel_noise_density_mps2_per_rthz = 100e-6 * 9.80665;
  f.accel_bias_sigma_mps2 = 1e-3 * 9.80665;
  return f;
}

Eigen::Matrix3d lever_arm_matrix(const Eigen::Vector3d& w_b_radps, const Eigen::Vector3d& dw_b_radps2) {
  const Eigen::Matrix3d W = skew(w_b_radps);
  return W * W + skew(dw_b_radps2);
}

Eigen::Vector3d specific_force_at_lever_arm(const AttitudeTruth& truth, const Eigen::Vector3d& lever_b_m,
                                            double gravity_mps2) {
  return truth.C_b_n.transpose() * Eigen::Vector3d(0.0, 0.0, -gravity_mps2) +
         lever_arm_matrix(truth.w_nb_b_radps, truth.dw_nb_b_radps2) * lever_b_m;
}

std::vector<ImuReading> simulate_lever_arm_imu(const std::vector<AttitudeTruth>& truth,
                                               const Eigen::Vector3d& lever_b_m, const MemsImuFigures& imu,
                                               double gravity_mps2, std::mt19937_64& rng) {
  if (truth.size() < 2) throw std::invalid_argument("lever-arm IMU: need at least 2 truth samples");
  const double dt = truth[1].t_s - truth[0].t_s;
  if (!(dt > 0.0)) throw std::invalid_argument("lever-arm IMU: truth samples must have increasing time");
  if (!(imu.gyro_drift_tau_s > 0.0)) throw std::invalid_argument("lever-arm IMU: gyro_drift_tau_s must be positive");
  std::normal_distribution<double> unit(0.0, 1.0);
  // Discrete first-order Markov: d_k+1 = a d_k + sigma sqrt(1 - a^2) n_k, started in steady state.
  const double a = std::exp(-dt / imu.gyro_drift_tau_s);
  Eigen::Vector3d drift = imu.gyro_drift_sigma_radps * gaussian3(unit, rng);
  const Eigen::Vector3d accel_bias = imu.accel_bias_sigma_mps2 * gaussian3(unit, rng);
  const double gyro_sigma = imu.gyro_noise_density_radps_per_rthz / std::sqrt(dt);
  const double accel_sigma = imu.accel_noise_density_mps2_per_rthz / std::sqrt(dt);
  std::vector<ImuReading> out;
  out.reserve(truth.size());
  for (const AttitudeTruth& s : truth) {
    ImuReading r;
    r.t_s = s.t_s;
    r.f_b_mps2 =
        specific_force_at_lever_arm(s, lever_b_m, gravity_mps2) + accel_bias + accel_sigma * gaussian3(unit, rng);
    r.w_ib_b_radps = s.w_nb_b_radps + drift + gyro_sigma * gaussian3(unit, rng);
    out.push_back(r);
    drift = a * drift + imu.gyro_drift_sigma_radps * std::sqrt(1.0 - a * a) * gaussian3(unit, rng);
  }
  return out;
}

}  // namespace deepnav
