#pragma once
// The one Kalman filter of the project: the GNSS/INS navigator's error states
// (aiding/aided_navigator), the stationary fine alignment and the lever-arm attitude EKF
// (this folder) all predict, update, gate and check through it; each keeps only its own
// models (transition, process noise, measurement rows).
//
// State x (N), covariance P (N x N); N fixed at compile time or Eigen::Dynamic.
//   predict             x = Phi x, P = Phi P Phi^T + Qd
//   predict_covariance  P alone, for an EKF that moves its (nonlinear) state itself
//   update              rows z = H x + v, v ~ N(0, diag r), independent rows;
//                       innovation nu = z - H x (update) or given by the caller
//                       (update_innovation: nu = z - h(x) of an EKF);
//                       S = H P H^T + diag r, K = P H^T S^-1 (an LDLT solve), x += K nu,
//                       P = (I - K H) P (I - K H)^T + K diag(r) K^T   (Joseph form)
// The Joseph form stays symmetric and positive semi-definite where the short form
// (I - K H) P loses both to round-off over long runs.
//
// Innovation gating, against the prior, before anything is changed:
//   per row: d_i = nu_i / sqrt(S_ii), a chi-square test with one degree of freedom
//     (d_i^2 <= g^2, written |d_i| <= g): rows beyond InnovationGate::row_sigma, and rows
//     whose d_i is not finite, are dropped and the update goes on with the rest;
//   jointly (optional): the normalised innovation squared of the rows kept,
//     NIS = nu^T S^-1 nu, chi-square with as many degrees of freedom as rows; above
//     InnovationGate::max_nis the whole update is refused.
//
// Health. What the caller hands in must be a covariance: P0 and every Qd symmetric, to a
// relative tolerance that round-off passes (|A_ij - A_ji| against sqrt(A_ii A_jj)). What
// the filter computes is made exactly symmetric after every step (the products above
// differ from their transposes by round-off, which in an ill-conditioned update can be a
// large fraction of a small entry), then x and P must be finite and every variance
// positive (or, where the policy allows it, zero: a state known exactly). A filter that
// fails is unhealthy (healthy() false, reason() says why) and refuses every further step
// until reset, so no NaN ever reaches an output.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepnav {

/// Which innovations an update turns away (0 switches a test off).
struct InnovationGate {
  double row_sigma = 0.0;  ///< per row: |nu_i| / sqrt(S_ii) above this drops the row
  double max_nis = 0.0;    ///< the rows kept together: NIS above this refuses the update
};

/// What the health check accepts.
struct KalmanHealthPolicy {
  /// false: every variance must be positive; true: zero is accepted too (a state the
  /// filter carries but knows exactly or never excites), a negative one never.
  bool allow_zero_variance = false;
  /// Largest |A_ij - A_ji| accepted in P0 and Qd, relative to sqrt(|A_ii A_jj|) + |A_ij| + |A_ji|.
  double symmetry_tolerance = 1e-9;
};

/// Outcome of one measurement update.
struct KalmanUpdate {
  bool applied = false;
  int rows = 0;                                ///< rows offered (kept or not)
  int rejected = 0;                            ///< rows not used (gated, not finite, or refused by the NIS test)
  double max_normalized_innovation = 0.0;      ///< largest |nu| / sqrt(S_ii) among the rows kept
  double nis = 0.0;                            ///< nu^T S^-1 nu of the rows kept (0 when none)
  bool nis_rejected = false;                   ///< the joint test refused the update
  std::vector<double> normalized_innovations;  ///< per row offered: nu / sqrt(S_ii) against the prior
  std::vector<bool> row_rejected;              ///< per row offered: not used
};

template <int N>
class KalmanFilter {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  using Row = Eigen::Matrix<double, 1, N>;

  KalmanFilter(const Vector& x0, const Matrix& P0, KalmanHealthPolicy policy = {}) : policy_(policy) { reset(x0, P0); }

  /// Starts again from x0, P0 (healthy again unless they fail the check).
  /// Throws std::invalid_argument when the sizes of x0 and P0 disagree.
  void reset(const Vector& x0, const Matrix& P0) {
    if (P0.rows() != x0.size() || P0.cols() != x0.size())
      throw std::invalid_argument("Kalman filter: covariance is " + std::to_string(P0.rows()) + " x " +
                                  std::to_string(P0.cols()) + " for " + std::to_string(x0.size()) + " states");
    x_ = x0;
    P_ = P0;
    healthy_ = true;
    reason_.clear();
    if (!symmetric(P0, "initial covariance")) return;
    check();
  }

  void predict(const Matrix& Phi, const Matrix& Qd) {
    if (!healthy_ || !symmetric(Qd, "process noise")) return;
    x_ = Phi * x_;
    P_ = Phi * P_ * Phi.transpose() + Qd;
    check();
  }

  /// The covariance over a step whose state the caller has already propagated.
  void predict_covariance(const Matrix& Phi, const Matrix& Qd) {
    if (!healthy_ || !symmetric(Qd, "process noise")) return;
    P_ = Phi * P_ * Phi.transpose() + Qd;
    check();
  }

  /// Linear rows: z = H x + v, r_diag the variance of each row's v. Throws
  /// std::invalid_argument when the sizes of z, H and r_diag disagree with each other or
  /// with the state.
  KalmanUpdate update(const Eigen::VectorXd& z, const Eigen::MatrixXd& H, const Eigen::VectorXd& r_diag,
                      const InnovationGate& gate = {}) {
    check_sizes(z, H, r_diag);
    if (!healthy_ || z.size() == 0) return {};
    const Eigen::VectorXd nu = z - H * x_;
    return update_with(nu, H, r_diag, gate);
  }

  /// Rows of an EKF: the caller's innovation nu = z - h(x) and the Jacobian H of h at x.
  KalmanUpdate update_innovation(const Eigen::VectorXd& nu, const Eigen::MatrixXd& H, const Eigen::VectorXd& r_diag,
                                 const InnovationGate& gate = {}) {
    check_sizes(nu, H, r_diag);
    if (!healthy_ || nu.size() == 0) return {};
    return update_with(nu, H, r_diag, gate);
  }

  /// A row's innovation over its predicted sigma against the current state, without an update.
  double normalized_innovation(double z, const Row& h, double r) const {
    const double s = h * P_ * h.transpose() + r;
    return (z - h * x_) / std::sqrt(s);
  }

  const Vector& x() const { return x_; }
  /// The state, for an EKF's own corrections (renormalising a quaternion); the next step checks it.
  Vector& x() { return x_; }
  const Matrix& P() const { return P_; }
  int size() const { return static_cast<int>(x_.size()); }

  /// Makes state `index` independent of the others with variance sigma^2 and estimate 0
  /// (a state taken on mid-run: what was known about it no longer holds).
  void reopen_state(int index, double sigma) {
    P_.row(index).setZero();
    P_.col(index).setZero();
    P_(index, index) = sigma * sigma;
    x_(index) = 0.0;
  }
  /// Adds sigma^2 to state `index`'s variance (what the filter knew of it may be wrong).
  void add_variance(int index, double sigma) { P_(index, index) += sigma * sigma; }
  /// Zeroes the state: a closed-loop error-state filter has fed its estimate back.
  void clear_state() { x_.setZero(); }

  bool healthy() const { return healthy_; }
  const std::string& reason() const { return reason_; }

 private:
  void check_sizes(const Eigen::VectorXd& z, const Eigen::MatrixXd& H, const Eigen::VectorXd& r_diag) const {
    if (H.rows() != z.size() || r_diag.size() != z.size() || H.cols() != x_.size())
      throw std::invalid_argument("Kalman update: " + std::to_string(z.size()) + " rows, H " +
                                  std::to_string(H.rows()) + " x " + std::to_string(H.cols()) + ", " +
                                  std::to_string(r_diag.size()) + " variances for " + std::to_string(x_.size()) +
                                  " states");
  }

  KalmanUpdate update_with(const Eigen::VectorXd& nu_all, const Eigen::MatrixXd& H, const Eigen::VectorXd& r_diag,
                           const InnovationGate& gate) {
    KalmanUpdate result;
    const Eigen::Index offered = nu_all.size();
    result.rows = static_cast<int>(offered);
    std::vector<Eigen::Index> keep;
    result.normalized_innovations.resize(static_cast<std::size_t>(offered));
    result.row_rejected.assign(static_cast<std::size_t>(offered), false);
    for (Eigen::Index i = 0; i < offered; ++i) {
      const double s = H.row(i) * P_ * H.row(i).transpose() + r_diag(i);
      const double normalized = nu_all(i) / std::sqrt(s);
      const double ratio = std::abs(normalized);
      result.normalized_innovations[static_cast<std::size_t>(i)] = normalized;
      if (!std::isfinite(ratio) || (gate.row_sigma > 0.0 && ratio > gate.row_sigma)) {
        ++result.rejected;
        result.row_rejected[static_cast<std::size_t>(i)] = true;
        continue;
      }
      result.max_normalized_innovation = std::max(result.max_normalized_innovation, ratio);
      keep.push_back(i);
    }
    if (keep.empty()) return result;
    const auto m = static_cast<Eigen::Index>(keep.size());
    const Eigen::Index n = P_.rows();
    Eigen::MatrixXd Hk(m, n);
    Eigen::VectorXd nu(m), r(m);
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index row = keep[static_cast<std::size_t>(k)];
      Hk.row(k) = H.row(row);
      nu(k) = nu_all(row);
      r(k) = r_diag(row);
    }
    const Eigen::MatrixXd PHt = P_ * Hk.transpose();
    Eigen::MatrixXd S = Hk * PHt;
    S.diagonal() += r;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(S);
    result.nis = nu.dot(ldlt.solve(nu));
    if (gate.max_nis > 0.0 && !(result.nis <= gate.max_nis)) {
      result.nis_rejected = true;
      result.rejected = result.rows;
      result.row_rejected.assign(static_cast<std::size_t>(offered), true);
      return result;
    }
    const Eigen::MatrixXd K = ldlt.solve(PHt.transpose()).transpose();
    x_ += K * nu;
    const Matrix IKH = Matrix::Identity(n, n) - K * Hk;
    P_ = IKH * P_ * IKH.transpose() + K * r.asDiagonal() * K.transpose();
    result.applied = true;
    check();
    return result;
  }

  /// Whether a covariance the caller supplies is symmetric; if not, the filter turns
  /// unhealthy naming `what` and the worst entry pair. (NaN passes here: check() names it.)
  bool symmetric(const Matrix& A, const char* what) {
    const Eigen::Index n = A.rows();
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = j + 1; i < n; ++i) {
        const double difference = std::abs(A(i, j) - A(j, i));
        const double scale = std::sqrt(std::abs(A(i, i) * A(j, j))) + std::abs(A(i, j)) + std::abs(A(j, i));
        if (difference > policy_.symmetry_tolerance * scale) {
          healthy_ = false;
          reason_ = std::string(what) + " is not symmetric: entries (" + std::to_string(i) + ", " + std::to_string(j) +
                    ") and (" + std::to_string(j) + ", " + std::to_string(i) + ") differ";
          return false;
        }
      }
    }
    return true;
  }

  /// Makes P exactly symmetric, then checks finiteness and the variances.
  void check() {
    const Eigen::Index n = P_.rows();
    P_ = 0.5 * (P_ + P_.transpose()).eval();
    if (!x_.allFinite() || !P_.allFinite()) {
      healthy_ = false;
      reason_ = "non-finite state or covariance";
      return;
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double variance = P_(i, i);
      if (policy_.allow_zero_variance ? !(variance >= 0.0) : !(variance > 0.0)) {
        healthy_ = false;
        reason_ = "variance of state " + std::to_string(i) + " is " +
                  (policy_.allow_zero_variance ? "negative" : "not positive");
        return;
      }
    }
  }

  KalmanHealthPolicy policy_;
  Vector x_;
  Matrix P_;
  bool healthy_ = true;
  std::string reason_;
};

}  // namespace deepnav
