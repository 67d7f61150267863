#include "receiver/pvt/raim.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <stdexcept>

namespace deepnav {

double chi_square_threshold(int dof, double false_alarm_probability) {
  if (dof < 1) throw std::invalid_argument("chi_square_threshold: needs at least 1 degree of freedom");
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 1.0))
    throw std::invalid_argument("chi_square_threshold: false-alarm probability must lie in (0, 1)");
  const boost::math::chi_squared_distribution<double> chi2(dof);
  return boost::math::quantile(boost::math::complement(chi2, false_alarm_probability));
}

namespace {

/// Standardised residuals r_i / sqrt(C_r,ii) with the normal matrix of type Normal (fixed
/// 4 x 4 for one clock, dynamic otherwise).
template <typename Normal>
void standardise(const Eigen::MatrixXd& H, const Eigen::VectorXd& w, const Eigen::VectorXd& r, ResidualTest& t) {
  const Eigen::Index n = H.rows();
  // C_r,ii = sigma_i^2 - h_i (H'WH)^-1 h_i': the part of satellite i's error the fit
  // cannot absorb. It stays positive with redundancy; a tiny floor keeps a satellite the
  // fix depends on entirely (no redundancy in its direction) from dividing by zero.
  const Normal N = H.transpose() * w.asDiagonal() * H;
  const Eigen::MatrixXd NiHt = N.ldlt().solve(H.transpose());
  t.standardised.resize(n);
  double worst = -1.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double var = std::max(1.0 / w(i) - H.row(i).dot(NiHt.col(i)), 1e-12 / w(i));
    t.standardised(i) = r(i) / std::sqrt(var);
    if (std::abs(t.standardised(i)) > worst) {
      worst = std::abs(t.standardised(i));
      t.worst_row = i;
    }
  }
}

}  // namespace

ResidualTest residual_test(const Eigen::MatrixXd& H, const Eigen::VectorXd& w, const Eigen::VectorXd& r,
                           double false_alarm_probability) {
  const Eigen::Index n = H.rows(), m = H.cols();
  if (m < 4 || n < m + 1 || w.size() != n || r.size() != n)
    throw std::invalid_argument("residual_test: needs n >= m + 1 rows of H (n x m, m >= 4), w and r");
  ResidualTest t;
  t.dof = static_cast<int>(n - m);
  t.statistic = r.dot(w.asDiagonal() * r);
  t.threshold = chi_square_threshold(t.dof, false_alarm_probability);
  t.fault_detected = t.statistic > t.threshold;
  if (m == 4) standardise<Eigen::Matrix4d>(H, w, r, t);
  else standardise<Eigen::MatrixXd>(H, w, r, t);
  return t;
}

}  // namespace deepnav
