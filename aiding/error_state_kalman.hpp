#pragma once
// The Kalman filter over the 17 error states: prediction with a transition matrix and
// discrete process noise, and sequential-block measurement updates in Joseph form
// (P = (I - K H) P (I - K H)^T + K R K^T), which stays symmetric positive definite
// where the short form loses it to round-off over long runs. After every step the
// covariance is symmetrised and checked: a non-finite or non-positive variance makes
// the filter unhealthy (healthy() false, reason()), and it refuses further updates
// until reset, so no NaN ever reaches a navigation output.
#include <string>
#include <vector>

#include "aiding/error_state.hpp"

namespace deepnav::aiding {

/// Outcome of one measurement update.
struct UpdateResult {
  bool applied = false;
  int rows = 0;                 ///< rows offered (kept or not)
  int rejected = 0;             ///< rows dropped by the innovation gate
  double max_normalized_innovation = 0.0;  ///< largest |nu| / sqrt(S_ii) among the rows kept
  std::vector<double> normalized_innovations;  ///< per row offered: nu / sqrt(S_ii) against the prior
  std::vector<bool> row_rejected;              ///< per row offered: turned away by the gate
};

class ErrorStateKalman {
 public:
  ErrorStateKalman(const StateVector& x0, const StateMatrix& P0);

  void predict(const StateMatrix& Phi, const StateMatrix& Qd);
  /// z = H x + v, v ~ N(0, R) with diagonal R (one entry per row). Rows whose normalised
  /// innovation exceeds `gate_sigma` are dropped first (0 disables the gate).
  template <int Rows>
  UpdateResult update(const Eigen::Matrix<double, Rows, 1>& z, const Eigen::Matrix<double, Rows, kStates>& H,
                      const Eigen::Matrix<double, Rows, 1>& r_diag, double gate_sigma = 0.0);
  /// The same for a run-time number of rows.
  UpdateResult update(const Eigen::VectorXd& z, const Eigen::MatrixXd& H, const Eigen::VectorXd& r_diag,
                      double gate_sigma = 0.0);

  /// A row's innovation over its predicted sigma against the current state, without an update.
  double normalized_innovation(double z, const StateRow& h, double r) const;

  const StateVector& x() const { return x_; }
  StateVector& x() { return x_; }
  const StateMatrix& P() const { return P_; }
  /// Makes state `index` independent of the others with variance sigma^2 (a state taken
  /// on mid-run: what was known about it no longer holds).
  void reopen_state(int index, double sigma);
  /// Adds sigma^2 to state `index`'s variance (what the filter knew of it may be wrong).
  void add_variance(int index, double sigma) { P_(index, index) += sigma * sigma; }
  /// Zeroes the error states once they have been fed back.
  void clear_fed_back_states();
  void reset(const StateVector& x0, const StateMatrix& P0);

  bool healthy() const { return healthy_; }
  const std::string& reason() const { return reason_; }

 private:
  void check();
  StateVector x_;
  StateMatrix P_;
  bool healthy_ = true;
  std::string reason_;
};

template <int Rows>
UpdateResult ErrorStateKalman::update(const Eigen::Matrix<double, Rows, 1>& z,
                                      const Eigen::Matrix<double, Rows, kStates>& H,
                                      const Eigen::Matrix<double, Rows, 1>& r_diag, double gate_sigma) {
  return update(Eigen::VectorXd(z), Eigen::MatrixXd(H), Eigen::VectorXd(r_diag), gate_sigma);
}

}  // namespace deepnav::aiding
