#include "ins/ship_roll_model.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace deepnav {
namespace {

/// Truth from Euler angles (roll, pitch, yaw) and their first and second derivatives.
/// Body rate w = E(eta) eta' and its derivative w' = E eta'' + E' eta' (ZYX Euler).
AttitudeTruth truth_from_euler(double t_s, const Eigen::Vector3d& eta, const Eigen::Vector3d& deta,
                               const Eigen::Vector3d& ddeta) {
  const double sp = std::sin(eta.x()), cp = std::cos(eta.x());
  const double st = std::sin(eta.y()), ct = std::cos(eta.y());
  Eigen::Matrix3d E;
  E << 1.0, 0.0, -st,    //
      0.0, cp, sp * ct,  //
      0.0, -sp, cp * ct;
  Eigen::Matrix3d dE;
  dE << 0.0, 0.0, -ct * deta.y(),                                    //
      0.0, -sp * deta.x(), cp * ct * deta.x() - sp * st * deta.y(),  //
      0.0, -cp * deta.x(), -sp * ct * deta.x() - cp * st * deta.y();
  AttitudeTruth out;
  out.t_s = t_s;
  out.C_b_n =
      (Eigen::AngleAxisd(eta.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(eta.y(), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(eta.x(), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  out.w_nb_b_radps = E * deta;
  out.dw_nb_b_radps2 = E * ddeta + dE * deta;
  out.roll_rad = eta.x();
  return out;
}

std::size_t sample_count(double duration_s, double rate_hz, const char* who) {
  if (!(duration_s > 0.0) || !(rate_hz > 0.0))
    throw std::invalid_argument(std::string(who) + ": duration_s and sample_rate_hz must be positive");
  return static_cast<std::size_t>(std::llround(duration_s * rate_hz)) + 1;
}

}  // namespace

std::vector<AttitudeTruth> simulate_ship_roll(const ShipRollParameters& p) {
  const std::size_t n = sample_count(p.duration_s, p.sample_rate_hz, "ship roll");
  if (!(p.roll_inertia_kgm2 > 0.0) || !(p.mass_kg > 0.0) || !(p.metacentric_height_m > 0.0))
    throw std::invalid_argument("ship roll: mass_kg, roll_inertia_kgm2 and metacentric_height_m must be positive");
  const double stiffness = p.mass_kg * p.gravity_mps2 * p.metacentric_height_m;  // righting moment per rad
  const double damping = 2.0 * p.damping_ratio * std::sqrt(stiffness * p.roll_inertia_kgm2);
  auto moment = [&](double t) {
    if (t < p.moment_start_s || t > p.moment_end_s) return 0.0;
    return p.moment_amplitude_Nm * std::sin(2.0 * std::numbers::pi * (t - p.moment_start_s) / p.moment_period_s);
  };
  auto accel = [&](double t, double phi, double dphi) {
    return (moment(t) - damping * dphi - stiffness * phi) / p.roll_inertia_kgm2;
  };
  std::vector<AttitudeTruth> out;
  out.reserve(n);
  constexpr int kSubsteps = 10;
  const double dt = 1.0 / p.sample_rate_hz;
  const double h = dt / kSubsteps;
  double phi = 0.0, dphi = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;  // from the integer counter: no drifting time
    out.push_back(truth_from_euler(t, {phi, 0.0, 0.0}, {dphi, 0.0, 0.0}, {accel(t, phi, dphi), 0.0, 0.0}));
    for (int k = 0; k < kSubsteps; ++k) {  // RK4 on (phi, phi')
      const double ts = t + k * h;
      const double k1p = dphi, k1v = accel(ts, phi, dphi);
      const double k2p = dphi + 0.5 * h * k1v, k2v = accel(ts + 0.5 * h, phi + 0.5 * h * k1p, k2p);
      const double k3p = dphi + 0.5 * h * k2v, k3v = accel(ts + 0.5 * h, phi + 0.5 * h * k2p, k3p);
      const double k4p = dphi + h * k3v, k4v = accel(ts + h, phi + h * k3p, k4p);
      phi += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
      dphi += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
  }
  return out;
}

std::vector<AttitudeTruth> simulate_rate_table(const RateTableParameters& p) {
  const std::size_t n = sample_count(p.duration_s, p.sample_rate_hz, "rate table");
  if (!(p.period_s > 0.0) || !(p.ramp_s > 0.0))
    throw std::invalid_argument("rate table: period_s and ramp_s must be positive");
  const double w = 2.0 * std::numbers::pi / p.period_s;
  const double wr = std::numbers::pi / p.ramp_s;
  std::vector<AttitudeTruth> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / p.sample_rate_hz;
    const double u = t - p.start_s;
    // Raised-cosine envelope s(u) over the ramp, with its derivatives.
    double s = 0.0, ds = 0.0, dds = 0.0;
    if (u >= p.ramp_s) {
      s = 1.0;
    } else if (u > 0.0) {
      s = 0.5 * (1.0 - std::cos(wr * u));
      ds = 0.5 * wr * std::sin(wr * u);
      dds = 0.5 * wr * wr * std::cos(wr * u);
    }
    const double su = std::sin(w * u), cu = std::cos(w * u);
    const double A = p.amplitude_rad;
    const double roll = A * s * su;
    const double droll = A * (ds * su + s * w * cu);
    const double ddroll = A * (dds * su + 2.0 * ds * w * cu - s * w * w * su);
    out.push_back(truth_from_euler(t, {roll, 0.0, 0.0}, {droll, 0.0, 0.0}, {ddroll, 0.0, 0.0}));
  }
  return out;
}

std::vector<AttitudeTruth> simulate_euler_oscillation(const EulerOscillationParameters& p) {
  const std::size_t n = sample_count(p.duration_s, p.sample_rate_hz, "Euler oscillation");
  if ((p.period_s.array() <= 0.0).any())
    throw std::invalid_argument("Euler oscillation: every period_s must be positive");
  const Eigen::Array3d w = 2.0 * std::numbers::pi / p.period_s.array();
  std::vector<AttitudeTruth> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / p.sample_rate_hz;
    const Eigen::Array3d arg = w * t + p.phase_rad.array();
    const Eigen::Array3d A = p.amplitude_rad.array();
    const Eigen::Vector3d eta = A * arg.sin();
    const Eigen::Vector3d deta = A * w * arg.cos();
    const Eigen::Vector3d ddeta = -A * w * w * arg.sin();
    out.push_back(truth_from_euler(t, eta, deta, ddeta));
  }
  return out;
}

}  // namespace deepnav
