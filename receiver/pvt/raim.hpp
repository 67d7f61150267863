#pragma once
// Receiver autonomous integrity monitoring (RAIM) of a weighted least-squares fix: the
// fault detection test and the identification statistic of fault detection and exclusion
// (FDE), after Brown (1992) and Walter & Enge (1995).
//
// Detection: with n satellites and m unknowns (position and one clock: 4; position, the GPS
// clock and the Galileo offset of a two-system fix: 5), the weighted sum of squared
// residuals r' W r is chi-square with n - m degrees of freedom when every pseudorange
// error is zero-mean Gaussian with the modelled sigma; a fault is declared when it exceeds
// the quantile at the configured false-alarm probability. Needs n >= m + 1.
//
// Identification: the post-fit residual covariance is C_r = (I - H (H'WH)^-1 H'W) W^-1,
// so the standardised residual of satellite i is r_i / sqrt(C_r,ii). Under a single fault
// it is largest at the faulty satellite in expectation; the weighted residual r_i^2 w_i
// alone is not (a satellite the geometry leans on hides most of its error in the fix).
#include <Eigen/Core>

namespace deepnav {

/// Chi-square quantile: the value exceeded with probability `false_alarm_probability`
/// by a chi-square variable with `dof` (>= 1) degrees of freedom (Boost.Math).
double chi_square_threshold(int dof, double false_alarm_probability);

struct ResidualTest {
  int dof = 0;                   ///< n - m
  double statistic = 0.0;        ///< r' W r (dimensionless)
  double threshold = 0.0;        ///< chi-square quantile at the false-alarm probability
  bool fault_detected = false;   ///< statistic > threshold
  Eigen::VectorXd standardised;  ///< r_i / sqrt(C_r,ii), in the rows' order
  /// Row with the largest |standardised residual| (the one to exclude), -1 when none.
  Eigen::Index worst_row = -1;
};

/// The test for design matrix `H` (n x m: line-of-sight rows and the clock columns, m 4 or
/// 5), weights `w` = 1 / sigma^2 (1/m^2) and post-fit residuals `r` (m). Needs n >= m + 1.
ResidualTest residual_test(const Eigen::MatrixXd& H, const Eigen::VectorXd& w, const Eigen::VectorXd& r,
                           double false_alarm_probability);

}  // namespace deepnav
