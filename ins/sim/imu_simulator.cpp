#include "ins/sim/imu_simulator.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ins/frames.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

// 4-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 4> kNodes = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                          0.8611363115940526};
constexpr std::array<double, 4> kWeights = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                            0.3478548451374538};

}  // namespace

ImuRates ideal_imu_rates(const TrajectoryState& s, const Eigen::Vector3d& lever_arm_b_m) {
  const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
  const Eigen::Vector3d w_ie_n = earth_rate_ned_radps(llh.lat_rad);
  const Eigen::Vector3d w_en_n = transport_rate_ned_radps(llh, s.v_ned_mps);
  const Eigen::Vector3d g_n(0.0, 0.0, wgs84::normal_gravity_mps2(llh.lat_rad, llh.height_m));
  const Eigen::Matrix3d C_n_b = s.q_b_n.conjugate().toRotationMatrix();
  const Eigen::Vector3d w_in_n = w_ie_n + w_en_n;

  ImuRates out;
  out.t_s = s.t_s;
  out.w_ib_b_radps = s.w_nb_b_radps + C_n_b * w_in_n;
  out.f_b_mps2 = C_n_b * (s.a_ned_mps2 + (2.0 * w_ie_n + w_en_n).cross(s.v_ned_mps) - g_n);

  if (!lever_arm_b_m.isZero()) {
    // d/dt (C_n_b w_in_n) = -w_nb_b x C_n_b w_in_n + C_n_b dw_in_n/dt; the change of the
    // Earth rate in NED (w_ie * dL/dt, ~1e-9 rad/s^2) is left out.
    const Eigen::Vector3d dw_en_n = transport_rate_derivative_ned_radps2(llh, s.v_ned_mps, s.a_ned_mps2);
    const Eigen::Vector3d dw_ib_b = s.dw_nb_b_radps2 - s.w_nb_b_radps.cross(C_n_b * w_in_n) + C_n_b * dw_en_n;
    const Eigen::Vector3d& w = out.w_ib_b_radps;
    out.f_b_mps2 += dw_ib_b.cross(lever_arm_b_m) + w.cross(w.cross(lever_arm_b_m));
  }
  return out;
}

ImuSample ideal_imu_increment(const Trajectory& trajectory, double t0_s, double t1_s,
                              const Eigen::Vector3d& lever_arm_b_m) {
  const double half = 0.5 * (t1_s - t0_s), mid = 0.5 * (t0_s + t1_s);
  ImuSample out;
  out.t_s = t1_s;
  for (std::size_t i = 0; i < kNodes.size(); ++i) {
    const ImuRates r = ideal_imu_rates(trajectory.at(mid + half * kNodes[i]), lever_arm_b_m);
    out.dtheta_b_rad += kWeights[i] * half * r.w_ib_b_radps;
    out.dv_b_mps += kWeights[i] * half * r.f_b_mps2;
  }
  return out;
}

ImuSimulator::ImuSimulator(const Trajectory& trajectory, const ImuSimConfig& config, std::uint64_t seed)
    : trajectory_(trajectory),
      lever_arm_b_m_(config.lever_arm_b_m),
      rate_hz_(config.imu.sample_rate_hz),
      errors_(config.imu, seed) {
  if (!(rate_hz_ > 0.0) || !std::isfinite(rate_hz_)) {
    throw std::invalid_argument("IMU simulator: sample_rate_hz must be a positive number, got " +
                                std::to_string(rate_hz_));
  }
  const double duration = trajectory.duration_s();
  if (std::isfinite(duration)) {
    // Small tolerance so that 200 s at 100 Hz gives 20000 samples despite rounding.
    sample_count_ = static_cast<std::int64_t>(std::floor(duration * rate_hz_ + 1e-9));
  }
}

ImuSample ImuSimulator::next() {
  if (done()) throw std::out_of_range("IMU simulator: past the end of the trajectory");
  const std::int64_t k = next_index_++;
  const double t0 = static_cast<double>(k - 1) / rate_hz_;
  const double t1 = static_cast<double>(k) / rate_hz_;
  ImuSample s = ideal_imu_increment(trajectory_, t0, t1, lever_arm_b_m_);
  errors_.apply(t1 - t0, s.dtheta_b_rad, s.dv_b_mps);
  return s;
}

std::vector<ImuSample> simulate_imu(const Trajectory& trajectory, const ImuSimConfig& config, std::uint64_t seed) {
  ImuSimulator sim(trajectory, config, seed);
  if (sim.sample_count() == 0) {
    throw std::invalid_argument("simulate_imu: the trajectory is open-ended or shorter than one IMU interval");
  }
  std::vector<ImuSample> out;
  out.reserve(static_cast<std::size_t>(sim.sample_count()));
  while (!sim.done()) out.push_back(sim.next());
  return out;
}

}  // namespace deepnav
