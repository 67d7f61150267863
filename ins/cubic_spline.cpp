#include "ins/cubic_spline.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <stdexcept>

namespace deepnav {

CubicSpline::CubicSpline(std::vector<double> t, Eigen::MatrixXd values) : t_(std::move(t)), y_(std::move(values)) {
  const auto n = static_cast<Eigen::Index>(t_.size());
  if (n < 2 || y_.cols() != n) throw std::invalid_argument("cubic spline: need at least 2 samples, one per time");
  for (Eigen::Index i = 1; i < n; ++i) {
    if (!(t_[i] > t_[i - 1])) throw std::invalid_argument("cubic spline: times must increase strictly");
  }
  m_ = Eigen::MatrixXd::Zero(y_.rows(), n);
  if (n == 2) return;
  // Interior equations h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (slope_i - slope_{i-1}),
  // with M_0 = M_{n-1} = 0 (natural end conditions).
  const Eigen::Index m = n - 2;
  Eigen::SparseMatrix<double> a(m, m);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs(m, y_.rows());
  for (Eigen::Index i = 1; i <= m; ++i) {
    const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
    entries.emplace_back(i - 1, i - 1, 2.0 * (h0 + h1));
    if (i > 1) entries.emplace_back(i - 1, i - 2, h0);
    if (i < m) entries.emplace_back(i - 1, i, h1);
    rhs.row(i - 1) = (6.0 * ((y_.col(i + 1) - y_.col(i)) / h1 - (y_.col(i) - y_.col(i - 1)) / h0)).transpose();
  }
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  if (solver.info() != Eigen::Success) throw std::runtime_error("cubic spline: system could not be factorised");
  const Eigen::MatrixXd solution = solver.solve(rhs);
  m_.middleCols(1, m) = solution.transpose();
}

std::size_t CubicSpline::interval(double t) const {
  if (t < t_.front() || t > t_.back()) throw std::out_of_range("time outside the spline's span");
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const auto i = static_cast<std::size_t>(std::distance(t_.begin(), it));
  return std::min(i == 0 ? 0 : i - 1, t_.size() - 2);
}

void CubicSpline::evaluate(double t, Eigen::VectorXd& value, Eigen::VectorXd& d1, Eigen::VectorXd& d2) const {
  const std::size_t i = interval(t);
  const auto j = static_cast<Eigen::Index>(i);
  const double h = t_[i + 1] - t_[i];
  const double a = (t_[i + 1] - t) / h, b = (t - t_[i]) / h;
  const auto& y0 = y_.col(j);
  const auto& y1 = y_.col(j + 1);
  const auto& m0 = m_.col(j);
  const auto& m1 = m_.col(j + 1);
  value = a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * (h * h / 6.0);
  d1 = (y1 - y0) / h + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * (h / 6.0);
  d2 = a * m0 + b * m1;
}

Eigen::VectorXd CubicSpline::value(double t) const {
  Eigen::VectorXd v, d1, d2;
  evaluate(t, v, d1, d2);
  return v;
}

}  // namespace deepnav
