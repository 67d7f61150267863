#include "aiding/error_state_kalman.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <vector>

namespace deepnav::aiding {

ErrorStateKalman::ErrorStateKalman(const StateVector& x0, const StateMatrix& P0) { reset(x0, P0); }

void ErrorStateKalman::reset(const StateVector& x0, const StateMatrix& P0) {
  x_ = x0;
  P_ = P0;
  healthy_ = true;
  reason_.clear();
  check();
}

void ErrorStateKalman::predict(const StateMatrix& Phi, const StateMatrix& Qd) {
  if (!healthy_) return;
  x_ = Phi * x_;
  P_ = Phi * P_ * Phi.transpose() + Qd;
  check();
}

UpdateResult ErrorStateKalman::update(const Eigen::VectorXd& z, const Eigen::MatrixXd& H, const Eigen::VectorXd& r_diag,
                                      double gate_sigma) {
  UpdateResult result;
  if (!healthy_ || z.size() == 0) return result;
  result.rows = static_cast<int>(z.size());
  // Innovation gate, row by row against the prior.
  const Eigen::VectorXd nu_all = z - H * x_;
  std::vector<Eigen::Index> keep;
  result.normalized_innovations.resize(static_cast<std::size_t>(z.size()));
  result.row_rejected.assign(static_cast<std::size_t>(z.size()), false);
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double s = H.row(i) * P_ * H.row(i).transpose() + r_diag(i);
    const double normalized = nu_all(i) / std::sqrt(s);
    const double ratio = std::abs(normalized);
    result.normalized_innovations[static_cast<std::size_t>(i)] = normalized;
    if (!std::isfinite(ratio) || (gate_sigma > 0.0 && ratio > gate_sigma)) {
      ++result.rejected;
      result.row_rejected[static_cast<std::size_t>(i)] = true;
      continue;
    }
    result.max_normalized_innovation = std::max(result.max_normalized_innovation, ratio);
    keep.push_back(i);
  }
  if (keep.empty()) return result;
  const auto m = static_cast<Eigen::Index>(keep.size());
  Eigen::MatrixXd Hk(m, kStates);
  Eigen::VectorXd nu(m), r(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    Hk.row(k) = H.row(keep[static_cast<std::size_t>(k)]);
    nu(k) = nu_all(keep[static_cast<std::size_t>(k)]);
    r(k) = r_diag(keep[static_cast<std::size_t>(k)]);
  }
  const Eigen::MatrixXd PHt = P_ * Hk.transpose();
  Eigen::MatrixXd S = Hk * PHt;
  S.diagonal() += r;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(S);
  const Eigen::MatrixXd K = ldlt.solve(PHt.transpose()).transpose();
  x_ += K * nu;
  const StateMatrix IKH = StateMatrix::Identity() - K * Hk;
  P_ = IKH * P_ * IKH.transpose() + K * r.asDiagonal() * K.transpose();
  result.applied = true;
  check();
  return result;
}

double ErrorStateKalman::normalized_innovation(double z, const StateRow& h, double r) const {
  const double s = h * P_ * h.transpose() + r;
  return (z - h * x_) / std::sqrt(s);
}

void ErrorStateKalman::reopen_state(int index, double sigma) {
  P_.row(index).setZero();
  P_.col(index).setZero();
  P_(index, index) = sigma * sigma;
  x_(index) = 0.0;
}

void ErrorStateKalman::clear_fed_back_states() { x_.setZero(); }

void ErrorStateKalman::check() {
  P_ = 0.5 * (P_ + P_.transpose()).eval();
  if (!x_.allFinite() || !P_.allFinite()) {
    healthy_ = false;
    reason_ = "non-finite state or covariance";
    return;
  }
  for (int i = 0; i < kStates; ++i) {
    if (!(P_(i, i) > 0.0)) {
      healthy_ = false;
      reason_ = "variance of state " + std::to_string(i) + " is not positive";
      return;
    }
  }
}

}  // namespace deepnav::aiding
