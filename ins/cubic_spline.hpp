#pragma once
// Natural cubic spline through samples of a vector-valued function of time: C2, so
// velocity and acceleration taken from it are continuous. The second-derivative
// system is symmetric tridiagonal and is solved once with Eigen's sparse LDLT.
#include <Eigen/Core>
#include <vector>

namespace deepnav {

class CubicSpline {
 public:
  /// t must be strictly increasing with at least 2 samples; values has one column per sample.
  CubicSpline(std::vector<double> t, Eigen::MatrixXd values);

  double t_begin() const { return t_.front(); }
  double t_end() const { return t_.back(); }
  /// Value and first/second derivatives at t in [t_begin, t_end] (throws std::out_of_range outside).
  void evaluate(double t, Eigen::VectorXd& value, Eigen::VectorXd& d1, Eigen::VectorXd& d2) const;
  Eigen::VectorXd value(double t) const;

 private:
  std::size_t interval(double t) const;
  std::vector<double> t_;
  Eigen::MatrixXd y_;  ///< values, one column per sample
  Eigen::MatrixXd m_;  ///< second derivatives at the samples
};

}  // namespace deepnav
