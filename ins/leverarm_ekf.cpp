#include "ins/leverarm_ekf.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace deepnav {
namespace {

/// Omega(w) with q' = 1/2 Omega(w) q for q = [q0 q1 q2 q3] (paper 004 [docs/references.md] eq. 1, times 2).
Eigen::Matrix4d omega_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix4d m;
  m << 0.0, -w.x(), -w.y(), -w.z(),  //
      w.x(), 0.0, w.z(), -w.y(),     //
      w.y(), -w.z(), 0.0, w.x(),     //
      w.z(), w.y(), -w.x(), 0.0;
  return m;
}

/// Xi(q) with q' = 1/2 Xi(q) w; the paper's B (eq. 1) is -1/2 Xi(q).
Eigen::Matrix<double, 4, 3> xi_matrix(const Eigen::Vector4d& q) {
  Eigen::Matrix<double, 4, 3> m;
  m << -q(1), -q(2), -q(3),  //
      q(0), -q(3), q(2),     //
      q(3), q(0), -q(1),     //
      -q(2), q(1), q(0);
  return m;
}

Eigen::Quaterniond to_quaternion(const Eigen::Vector4d& q) { return {q(0), q(1), q(2), q(3)}; }
Eigen::Vector4d to_vector(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

int lever_state_count(LeverArmModel model) {
  switch (model) {
    case LeverArmModel::kNone:
      return 0;
    case LeverArmModel::kVertical:
      return 1;
    case LeverArmModel::kFull3d:
      return 3;
  }
  return 0;
}

std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(2);
  out << std::fixed << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

}  // namespace

LeverArmObservability assess_lever_arm_observability(const Eigen::Matrix3d& information, double sigma_limit_m) {
  LeverArmObservability out;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (information + information.transpose()));
  out.eigenvalues = eig.eigenvalues();
  out.directions = eig.eigenvectors();
  std::ostringstream summary;
  summary.precision(3);
  out.fully_observable = true;
  const double lambda_max = std::max(out.eigenvalues(2), 0.0);
  for (int k = 0; k < 3; ++k) {
    const double lambda = out.eigenvalues(k);
    out.sigma_m(k) = lambda > 0.0 ? 1.0 / std::sqrt(lambda) : std::numeric_limits<double>::infinity();
    if (out.sigma_m(k) <= sigma_limit_m) continue;
    out.fully_observable = false;
    Eigen::Vector3d dir = out.directions.col(k);
    if (dir.cwiseAbs().maxCoeff() == -dir.minCoeff()) dir = -dir;  // print the dominant component positive
    summary << (summary.tellp() > 0 ? "; " : "");
    // Information 100x below the best direction: the motion gives (almost) nothing, e.g. an
    // arm along the only rotation axis. Otherwise the motion is just too short or gentle.
    if (lambda < 1e-2 * lambda_max)
      summary << "not observable along body direction " << vector_text(dir) << " (sigma " << out.sigma_m(k)
              << " m): an arm along it makes no acceleration in this motion (rotation about that axis only)";
    else
      summary << "weakly observable along body direction " << vector_text(dir) << " (sigma " << out.sigma_m(k)
              << " m > " << sigma_limit_m << " m): needs more motion or time";
  }
  out.summary = out.fully_observable ? "observable in all three axes" : summary.str();
  return out;
}

LeverArmEkfConfig paper004_config(LeverArmModel model, const MemsImuFigures& imu, double gravity_mps2) {
  LeverArmEkfConfig c;
  c.model = model;
  c.gravity_mps2 = gravity_mps2;
  c.gyro_noise_density_radps_per_rthz = imu.gyro_noise_density_radps_per_rthz;
  c.gyro_drift_sigma_radps = imu.gyro_drift_sigma_radps;
  c.gyro_drift_tau_s = imu.gyro_drift_tau_s;
  c.accel_sigma_mps2 = 1.0;
  c.lever_psd_m2ps = 1e-6;
  c.initial_attitude_sigma_rad = 0.02;
  c.initial_lever_sigma_m = 1.0;
  return c;
}

LeverArmEkf::Filter LeverArmEkf::make_filter(const LeverArmEkfConfig& config, const Eigen::Quaterniond& q_b_n0) {
  const int lever_states = lever_state_count(config.model);
  const int n = 7 + lever_states;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  x.head<4>() = to_vector(q_b_n0.normalized());
  if (config.model == LeverArmModel::kVertical) x(7) = config.initial_lever_b_m.z();
  if (config.model == LeverArmModel::kFull3d) x.tail<3>() = config.initial_lever_b_m;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n, n);
  // Small-angle attitude uncertainty maps onto the quaternion through 1/2 Xi(q).
  const Eigen::Matrix<double, 4, 3> Xi = xi_matrix(x.head<4>());
  P.topLeftCorner<4, 4>() =
      0.25 * Xi * Xi.transpose() * config.initial_attitude_sigma_rad * config.initial_attitude_sigma_rad;
  const double drift0 =
      config.initial_drift_sigma_radps > 0.0 ? config.initial_drift_sigma_radps : config.gyro_drift_sigma_radps;
  P.block<3, 3>(4, 4) = Eigen::Matrix3d::Identity() * drift0 * drift0;
  if (lever_states > 0)
    P.bottomRightCorner(lever_states, lever_states) = Eigen::MatrixXd::Identity(lever_states, lever_states) *
                                                      config.initial_lever_sigma_m * config.initial_lever_sigma_m;
  return Filter(x, P, {.allow_zero_variance = true});
}

LeverArmEkf::LeverArmEkf(const LeverArmEkfConfig& config, const Eigen::Quaterniond& q_b_n0)
    : config_(config), lever_states_(lever_state_count(config.model)), kf_(make_filter(config, q_b_n0)) {
  if (!(config.gyro_drift_tau_s > 0.0)) throw std::invalid_argument("lever-arm EKF: gyro_drift_tau_s must be positive");
  if (!(config.accel_sigma_mps2 > 0.0)) throw std::invalid_argument("lever-arm EKF: accel_sigma_mps2 must be positive");
}

void LeverArmEkf::propagate(const Eigen::Vector3d& w_meas_radps, double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("lever-arm EKF: propagation step dt must be positive");
  const int n = state_size();
  const Eigen::Vector4d q = kf_.x().head<4>();
  const Eigen::Vector3d w = w_meas_radps - gyro_drift_radps();
  const double beta = 1.0 / config_.gyro_drift_tau_s;

  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(n, n);
  F.topLeftCorner<4, 4>() = 0.5 * omega_matrix(w);
  F.block<4, 3>(0, 4) = -0.5 * xi_matrix(q);
  F.block<3, 3>(4, 4) = -beta * Eigen::Matrix3d::Identity();
  const Eigen::MatrixXd Fdt = F * dt_s;
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n) + Fdt + 0.5 * Fdt * Fdt;

  Eigen::MatrixXd Qd = Eigen::MatrixXd::Zero(n, n);
  const Eigen::Matrix<double, 4, 3> Xi = xi_matrix(q);
  const double gyro_psd = config_.gyro_noise_density_radps_per_rthz * config_.gyro_noise_density_radps_per_rthz;
  Qd.topLeftCorner<4, 4>() = 0.25 * Xi * Xi.transpose() * gyro_psd * dt_s;
  const double a = std::exp(-beta * dt_s);
  Qd.block<3, 3>(4, 4) =
      Eigen::Matrix3d::Identity() * config_.gyro_drift_sigma_radps * config_.gyro_drift_sigma_radps * (1.0 - a * a);
  if (lever_states_ > 0)
    Qd.bottomRightCorner(lever_states_, lever_states_) =
        Eigen::MatrixXd::Identity(lever_states_, lever_states_) * config_.lever_psd_m2ps * dt_s;

  // State: exact rotation increment for the quaternion, exact Markov decay for the drift.
  const double angle = w.norm() * dt_s;
  const Eigen::Quaterniond dq =
      angle > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized())) : Eigen::Quaterniond::Identity();
  Eigen::VectorXd& x = kf_.x();
  x.head<4>() = to_vector((to_quaternion(q) * dq).normalized());
  x.segment<3>(4) *= a;
  kf_.predict_covariance(Phi, Qd);
}

Eigen::Matrix3d LeverArmEkf::lever_matrix(const Eigen::Vector3d& w_meas_radps, const Eigen::Vector3d& dw_radps2) const {
  return lever_arm_matrix(w_meas_radps - gyro_drift_radps(), dw_radps2);
}

void LeverArmEkf::update(const Eigen::Vector3d& f_meas_mps2, const Eigen::Vector3d& w_meas_radps,
                         const Eigen::Vector3d& dw_radps2) {
  if (!f_meas_mps2.allFinite() || !w_meas_radps.allFinite() || !dw_radps2.allFinite())
    throw std::invalid_argument("lever-arm EKF: non-finite accelerometer, rate or angular acceleration");
  const int n = state_size();
  const double g = config_.gravity_mps2;
  const Eigen::Vector4d q = kf_.x().head<4>();
  const Eigen::Matrix3d K_arm = lever_matrix(w_meas_radps, dw_radps2);
  const double r = config_.accel_sigma_mps2 * config_.accel_sigma_mps2;
  information_ += K_arm.transpose() * K_arm / r;

  // h(x), paper eq. 16: gravity through C_n^b(q) plus the lever-arm accelerations.
  const Eigen::Matrix3d C_b_n = to_quaternion(q).toRotationMatrix();
  Eigen::Vector3d h = C_b_n.transpose() * Eigen::Vector3d(0.0, 0.0, -g) + K_arm * lever_b_m();
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3, n);
  H.block<3, 4>(0, 0) << 2 * g * q(2), -2 * g * q(3), 2 * g * q(0), -2 * g * q(1),  // eq. 19
      -2 * g * q(1), -2 * g * q(0), -2 * g * q(3), -2 * g * q(2),                   //
      -2 * g * q(0), 2 * g * q(1), 2 * g * q(2), -2 * g * q(3);
  if (config_.model == LeverArmModel::kVertical) H.block<3, 1>(0, 7) = K_arm.col(2);
  if (config_.model == LeverArmModel::kFull3d) H.block<3, 3>(0, 7) = K_arm;

  if (kf_.update_innovation(f_meas_mps2 - h, H, Eigen::Vector3d::Constant(r)).applied) kf_.x().head<4>().normalize();
}

Eigen::Quaterniond LeverArmEkf::q_b_n() const { return to_quaternion(kf_.x().head<4>()); }

Eigen::Vector3d LeverArmEkf::lever_b_m() const {
  if (config_.model == LeverArmModel::kVertical) return {0.0, 0.0, kf_.x()(7)};
  if (config_.model == LeverArmModel::kFull3d) return kf_.x().tail<3>();
  return Eigen::Vector3d::Zero();
}

Eigen::Vector3d LeverArmEkf::lever_sigma_m() const {
  const Eigen::MatrixXd& P = kf_.P();
  if (config_.model == LeverArmModel::kVertical) return {0.0, 0.0, std::sqrt(P(7, 7))};
  if (config_.model == LeverArmModel::kFull3d) return P.bottomRightCorner<3, 3>().diagonal().cwiseSqrt();
  return Eigen::Vector3d::Zero();
}

LeverArmObservability LeverArmEkf::observability() const {
  return assess_lever_arm_observability(information_, config_.observability_sigma_limit_m);
}

std::vector<Eigen::Vector3d> smoothed_angular_acceleration(const std::vector<Eigen::Vector3d>& w_radps, double dt_s,
                                                           int half_window) {
  if (half_window < 1) throw std::invalid_argument("angular acceleration: half_window must be at least 1");
  if (!(dt_s > 0.0)) throw std::invalid_argument("angular acceleration: dt must be positive");
  const auto n = static_cast<long>(w_radps.size());
  std::vector<Eigen::Vector3d> out(w_radps.size(), Eigen::Vector3d::Zero());
  for (long i = 0; i < n; ++i) {
    const long lo = std::max(0L, i - half_window), hi = std::min(n - 1, i + half_window);
    if (hi <= lo) continue;
    const double t_mean = 0.5 * static_cast<double>(lo + hi);
    Eigen::Vector3d w_mean = Eigen::Vector3d::Zero();
    for (long j = lo; j <= hi; ++j) w_mean += w_radps[j];
    w_mean /= static_cast<double>(hi - lo + 1);
    Eigen::Vector3d num = Eigen::Vector3d::Zero();
    double den = 0.0;
    for (long j = lo; j <= hi; ++j) {
      const double dtj = static_cast<double>(j) - t_mean;
      num += dtj * (w_radps[j] - w_mean);
      den += dtj * dtj;
    }
    out[i] = num / (den * dt_s);
  }
  return out;
}

LeverArmEkfRun run_lever_arm_ekf(const std::vector<ImuReading>& imu, const LeverArmEkfConfig& config, int level_samples,
                                 int accel_half_window) {
  if (imu.size() < 2) throw std::invalid_argument("lever-arm EKF run: need at least 2 IMU readings");
  const std::size_t n_level =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(level_samples, 1)), 1, imu.size());
  Eigen::Vector3d f0 = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n_level; ++i) f0 += imu[i].f_b_mps2 / static_cast<double>(n_level);
  if (!f0.allFinite() || f0.norm() <= 0.0)
    throw std::invalid_argument("lever-arm EKF run: initial specific force is zero or not finite");
  const double roll0 = std::atan2(-f0.y(), -f0.z());
  const double pitch0 = std::atan2(f0.x(), std::hypot(f0.y(), f0.z()));
  const Eigen::Quaterniond q0 =
      Eigen::AngleAxisd(pitch0, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll0, Eigen::Vector3d::UnitX());

  std::vector<Eigen::Vector3d> rates;
  rates.reserve(imu.size());
  for (const ImuReading& r : imu) rates.push_back(r.w_ib_b_radps);
  const double dt = imu[1].t_s - imu[0].t_s;
  const std::vector<Eigen::Vector3d> dw = smoothed_angular_acceleration(rates, dt, accel_half_window);

  LeverArmEkf ekf(config, q0);
  LeverArmEkfRun run;
  auto record = [&](double t) {
    const Eigen::Matrix3d C = ekf.q_b_n().toRotationMatrix();
    run.t_s.push_back(t);
    run.roll_rad.push_back(std::atan2(C(2, 1), C(2, 2)));
    run.lever_b_m.push_back(ekf.lever_b_m());
  };
  record(imu[0].t_s);
  for (std::size_t k = 1; k < imu.size(); ++k) {
    const double step = imu[k].t_s - imu[k - 1].t_s;
    // Trapezoidal rate over the interval: the reading is a sample, not an average.
    ekf.propagate(0.5 * (imu[k - 1].w_ib_b_radps + imu[k].w_ib_b_radps), step);
    ekf.update(imu[k].f_b_mps2, imu[k].w_ib_b_radps, dw[k]);
    record(imu[k].t_s);
  }
  run.final_lever_sigma_m = ekf.lever_sigma_m();
  run.observability = ekf.observability();
  return run;
}

}  // namespace deepnav
