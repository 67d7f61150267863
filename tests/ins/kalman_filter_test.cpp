#include "ins/kalman_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace deepnav {
namespace {

using Filter4 = KalmanFilter<4>;
using FilterX = KalmanFilter<Eigen::Dynamic>;

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double value : values) v(i++) = value;
  return v;
}

TEST(KalmanFilter, ConstantEstimatedFromNoisyReadingsMatchesTheAnalyticPosterior) {
  // x constant, z_k = x + v_k, v_k ~ N(0, r). From prior (x0, p0) after k readings:
  //   1/p_k = 1/p0 + k/r,   x_k = p_k (x0/p0 + sum z / r).
  const double x0 = 2.0, p0 = 4.0, r = 0.25, truth = 1.3;
  FilterX kf(vec({x0}), Eigen::MatrixXd::Constant(1, 1, p0));
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, std::sqrt(r));
  const Eigen::MatrixXd H = Eigen::MatrixXd::Ones(1, 1);
  double sum_z = 0.0;
  for (int k = 1; k <= 400; ++k) {
    kf.predict(Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Zero(1, 1));  // a constant: no process noise
    const double z = truth + noise(rng);
    sum_z += z;
    ASSERT_TRUE(kf.update(vec({z}), H, vec({r})).applied);
    const double p_k = 1.0 / (1.0 / p0 + k / r);
    const double x_k = p_k * (x0 / p0 + sum_z / r);
    ASSERT_NEAR(kf.P()(0, 0), p_k, 1e-12 * p_k) << "after " << k << " readings";
    ASSERT_NEAR(kf.x()(0), x_k, 1e-12) << "after " << k << " readings";
  }
  EXPECT_NEAR(kf.x()(0), truth, 4.0 * std::sqrt(r / 400.0));
  EXPECT_TRUE(kf.healthy());
}

TEST(KalmanFilter, JosephFormKeepsTheCovarianceSymmetricAndPositiveSemiDefinite) {
  // Strongly correlated states, a wide prior and near-perfect measurements: the short
  // form (I - K H) P loses symmetry and definiteness here; the Joseph form must not.
  Filter4::Matrix A;
  A << 1.0, 0.9, 0.0, 0.3,   //
      0.0, 1.0, 0.99, 0.0,   //
      0.2, 0.0, 1.0, 0.999,  //
      0.0, 0.1, 0.0, 1.0;
  const Filter4::Matrix P0 = 1e6 * A * A.transpose();
  Filter4 kf(Filter4::Vector::Zero(), P0);
  Filter4::Matrix Phi = Filter4::Matrix::Identity();
  Phi(0, 1) = 0.01;
  Phi(1, 2) = 0.01;
  Phi(2, 3) = 0.01;
  const Filter4::Matrix Qd = 1e-12 * Filter4::Matrix::Identity();
  std::mt19937_64 rng(3);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int step = 0; step < 2000; ++step) {
    kf.predict(Phi, Qd);
    Eigen::MatrixXd H(2, 4);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 4; ++j) H(i, j) = unit(rng);
    const KalmanUpdate u = kf.update(Eigen::VectorXd::Zero(2), H, vec({1e-10, 1e-10}));
    ASSERT_TRUE(u.applied) << "step " << step;
    ASSERT_TRUE(kf.healthy()) << kf.reason();
    const Filter4::Matrix& P = kf.P();
    ASSERT_EQ(P, P.transpose()) << "exactly symmetric after step " << step;
    const double min_eigenvalue = Eigen::SelfAdjointEigenSolver<Filter4::Matrix>(P).eigenvalues().minCoeff();
    ASSERT_GE(min_eigenvalue, -1e-12 * P.diagonal().maxCoeff()) << "step " << step;
  }
}

TEST(KalmanFilter, RowGateDropsTheOutlierAndUsesTheRest) {
  Filter4 kf(Filter4::Vector::Zero(), Filter4::Matrix::Identity());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, 4);
  H(0, 0) = 1.0;
  H(1, 1) = 1.0;
  // Row 0: 0.5 sigma; row 1: 100 / sqrt(2) = 70.7 sigma against S = 1 + 1.
  const KalmanUpdate u = kf.update(vec({0.5, 100.0}), H, vec({1.0, 1.0}), {.row_sigma = 5.0});
  EXPECT_TRUE(u.applied);
  EXPECT_EQ(u.rows, 2);
  EXPECT_EQ(u.rejected, 1);
  EXPECT_FALSE(u.row_rejected[0]);
  EXPECT_TRUE(u.row_rejected[1]);
  EXPECT_NEAR(u.normalized_innovations[1], 100.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(u.max_normalized_innovation, 0.5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(kf.x()(0), 0.25, 1e-12);  // equal prior and measurement variance: half way
  EXPECT_EQ(kf.x()(1), 0.0);            // the outlier moved nothing
  EXPECT_EQ(kf.P()(1, 1), 1.0);
  EXPECT_NEAR(u.nis, 0.25 / 2.0, 1e-12);
}

TEST(KalmanFilter, NonFiniteRowsAreDroppedWithoutLosingHealth) {
  Filter4 kf(Filter4::Vector::Zero(), Filter4::Matrix::Identity());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, 4);
  H(0, 0) = 1.0;
  H(1, 1) = 1.0;
  const KalmanUpdate u = kf.update(vec({std::nan(""), 100.0}), H, vec({1.0, 1.0}), {.row_sigma = 5.0});
  EXPECT_FALSE(u.applied);
  EXPECT_EQ(u.rejected, 2);
  EXPECT_TRUE(kf.healthy());
  // Without a gate a non-finite row is still dropped.
  EXPECT_EQ(kf.update(vec({std::numeric_limits<double>::infinity()}), H.topRows(1), vec({1.0})).rejected, 1);
  EXPECT_TRUE(kf.healthy());
}

TEST(KalmanFilter, JointNisGateRefusesRowsThatAgreeOnABias) {
  // Three rows at 2.9 sigma each pass a 3-sigma row gate; together NIS = 3 * 2.9^2 = 25.2,
  // beyond the 99.9 % chi-square bound for 3 degrees of freedom (16.27).
  Filter4 kf(Filter4::Vector::Zero(), 1e-12 * Filter4::Matrix::Identity());
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(3, 4);
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(3, 2.9);
  const KalmanUpdate refused = kf.update(z, H, Eigen::VectorXd::Ones(3), {.row_sigma = 3.0, .max_nis = 16.27});
  EXPECT_FALSE(refused.applied);
  EXPECT_TRUE(refused.nis_rejected);
  EXPECT_EQ(refused.rejected, 3);
  EXPECT_NEAR(refused.nis, 3 * 2.9 * 2.9, 1e-9);
  EXPECT_EQ(kf.x(), Filter4::Vector::Zero());
  // The row gate alone lets them through.
  EXPECT_TRUE(kf.update(z, H, Eigen::VectorXd::Ones(3), {.row_sigma = 3.0}).applied);
}

TEST(KalmanFilter, HealthCheckCatchesANaNAndRefusesFurtherSteps) {
  Filter4 kf(Filter4::Vector::Zero(), Filter4::Matrix::Identity());
  Filter4::Matrix bad = Filter4::Matrix::Identity();
  bad(3, 3) = std::nan("");
  kf.predict(Filter4::Matrix::Identity(), bad);
  EXPECT_FALSE(kf.healthy());
  EXPECT_EQ(kf.reason(), "non-finite state or covariance");
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(1, 4);
  EXPECT_FALSE(kf.update(vec({1.0}), H, vec({1.0})).applied) << "an unhealthy filter takes no update";
  kf.reset(Filter4::Vector::Zero(), Filter4::Matrix::Identity());
  EXPECT_TRUE(kf.healthy());
  EXPECT_TRUE(kf.update(vec({1.0}), H, vec({1.0})).applied);
}

TEST(KalmanFilter, HealthCheckCatchesAsymmetryAndBadVariances) {
  Filter4::Matrix asymmetric = Filter4::Matrix::Identity();
  asymmetric(0, 1) = 0.1;  // a process noise that is not a covariance
  Filter4 kf(Filter4::Vector::Zero(), Filter4::Matrix::Identity());
  kf.predict(Filter4::Matrix::Identity(), asymmetric);
  EXPECT_FALSE(kf.healthy());
  EXPECT_EQ(kf.reason(), "process noise is not symmetric: entries (1, 0) and (0, 1) differ");
  EXPECT_EQ(kf.P(), Filter4::Matrix::Identity()) << "the step was not taken";
  const Filter4 bad_start(Filter4::Vector::Zero(), asymmetric);
  EXPECT_FALSE(bad_start.healthy());
  EXPECT_EQ(bad_start.reason(), "initial covariance is not symmetric: entries (1, 0) and (0, 1) differ");
  // Round-off is not asymmetry.
  Filter4::Matrix nearly = Filter4::Matrix::Identity();
  nearly(0, 1) = 0.1;
  nearly(1, 0) = 0.1 * (1.0 + 1e-14);
  EXPECT_TRUE(Filter4(Filter4::Vector::Zero(), nearly).healthy());

  Filter4::Matrix negative = Filter4::Matrix::Identity();
  negative(2, 2) = -1.0;
  Filter4 neg(Filter4::Vector::Zero(), negative);
  EXPECT_FALSE(neg.healthy());
  EXPECT_EQ(neg.reason(), "variance of state 2 is not positive");

  // A zero variance: refused by default, accepted where the policy allows it; a negative
  // one never.
  Filter4::Matrix zero = Filter4::Matrix::Identity();
  zero(1, 1) = 0.0;
  EXPECT_FALSE(Filter4(Filter4::Vector::Zero(), zero).healthy());
  EXPECT_TRUE(Filter4(Filter4::Vector::Zero(), zero, {.allow_zero_variance = true}).healthy());
  const Filter4 lenient_negative(Filter4::Vector::Zero(), negative, {.allow_zero_variance = true});
  EXPECT_FALSE(lenient_negative.healthy());
  EXPECT_EQ(lenient_negative.reason(), "variance of state 2 is negative");
}

TEST(KalmanFilter, EkfUpdateTakesTheCallersInnovation) {
  // h(x) = x^2 about x = 3: H = 2 x = 6; a reading of 9.6 gives nu = 0.6.
  FilterX kf(vec({3.0}), Eigen::MatrixXd::Constant(1, 1, 0.01));
  const KalmanUpdate u = kf.update_innovation(vec({0.6}), Eigen::MatrixXd::Constant(1, 1, 6.0), vec({0.04}));
  ASSERT_TRUE(u.applied);
  const double s = 36.0 * 0.01 + 0.04, k = 0.01 * 6.0 / s;
  EXPECT_NEAR(kf.x()(0), 3.0 + k * 0.6, 1e-14);
  EXPECT_NEAR(kf.P()(0, 0), (1 - 6 * k) * (1 - 6 * k) * 0.01 + k * k * 0.04, 1e-15);
}

TEST(KalmanFilter, CovarianceOnlyPredictionLeavesTheStateToTheCaller) {
  FilterX kf(vec({1.0, 2.0}), Eigen::MatrixXd::Identity(2, 2));
  Eigen::MatrixXd Phi(2, 2);
  Phi << 1.0, 0.5, 0.0, 1.0;
  kf.predict_covariance(Phi, 0.1 * Eigen::MatrixXd::Identity(2, 2));
  EXPECT_EQ(kf.x(), vec({1.0, 2.0}));
  EXPECT_DOUBLE_EQ(kf.P()(0, 0), 1.25 + 0.1);
  EXPECT_DOUBLE_EQ(kf.P()(0, 1), 0.5);
  kf.predict(Phi, Eigen::MatrixXd::Zero(2, 2));
  EXPECT_EQ(kf.x(), vec({2.0, 2.0}));
}

TEST(KalmanFilter, ReopenedStateIsIndependentAndMismatchedSizesAreRefused) {
  Filter4 kf(Filter4::Vector::Constant(1.0), Filter4::Matrix::Constant(0.5) + 0.5 * Filter4::Matrix::Identity());
  kf.reopen_state(2, 3.0);
  EXPECT_EQ(kf.x()(2), 0.0);
  EXPECT_EQ(kf.P()(2, 2), 9.0);
  EXPECT_EQ(kf.P().row(2).sum(), 9.0);
  EXPECT_EQ(kf.P().col(2).sum(), 9.0);
  kf.clear_state();
  EXPECT_EQ(kf.x(), Filter4::Vector::Zero());
  EXPECT_THROW(FilterX(vec({1.0, 2.0}), Eigen::MatrixXd::Identity(3, 3)), std::invalid_argument);
  EXPECT_THROW(kf.update(vec({1.0}), Eigen::MatrixXd::Identity(1, 3), vec({1.0})), std::invalid_argument);
  EXPECT_THROW(kf.update(vec({1.0, 2.0}), Eigen::MatrixXd::Identity(2, 4), vec({1.0})), std::invalid_argument);
  EXPECT_THROW(kf.update_innovation(vec({1.0}), Eigen::MatrixXd::Identity(2, 4), vec({1.0})), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
