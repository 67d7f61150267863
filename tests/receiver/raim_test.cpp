#include "receiver/pvt/raim.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>

namespace deepnav {
namespace {

TEST(Raim, ChiSquareThresholdMatchesTables) {
  // Upper-tail quantiles (e.g. NIST/SEMATECH table): 10.828 (1 dof), 18.467 (4), 29.588 (10) at 1e-3.
  EXPECT_NEAR(chi_square_threshold(1, 1e-3), 10.828, 1e-3);
  EXPECT_NEAR(chi_square_threshold(4, 1e-3), 18.467, 1e-3);
  EXPECT_NEAR(chi_square_threshold(10, 1e-3), 29.588, 1e-3);
  EXPECT_NEAR(chi_square_threshold(2, 0.05), 5.991, 1e-3);
  EXPECT_THROW(chi_square_threshold(0, 1e-3), std::invalid_argument);
  EXPECT_THROW(chi_square_threshold(3, 0.0), std::invalid_argument);
}

/// Eight unit lines of sight spread over the sky and the clock column.
Eigen::MatrixXd geometry() {
  Eigen::MatrixXd H(8, 4);
  const double el[] = {80, 60, 45, 30, 20, 15, 50, 35}, az[] = {0, 45, 100, 170, 220, 280, 320, 250};
  for (int i = 0; i < 8; ++i) {
    const double e = el[i] * M_PI / 180.0, a = az[i] * M_PI / 180.0;
    H.row(i) << -std::cos(e) * std::sin(a), -std::cos(e) * std::cos(a), -std::sin(e), 1.0;
  }
  return H;
}

TEST(Raim, StandardisedResidualsHaveUnitVarianceWithoutFault) {
  const Eigen::MatrixXd H = geometry();
  Eigen::VectorXd w(8);
  w << 4.0, 2.0, 1.0, 0.5, 0.3, 0.25, 1.5, 0.8;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::VectorXd sum2 = Eigen::VectorXd::Zero(8);
  int detections = 0;
  constexpr int kRuns = 20000;
  const Eigen::MatrixXd P = H * (H.transpose() * w.asDiagonal() * H).inverse() * H.transpose() * w.asDiagonal();
  for (int k = 0; k < kRuns; ++k) {
    Eigen::VectorXd e(8);
    for (int i = 0; i < 8; ++i) e(i) = n(rng) / std::sqrt(w(i));
    const Eigen::VectorXd r = e - P * e;  // post-fit residuals
    const ResidualTest t = residual_test(H, w, r, 1e-2);
    EXPECT_EQ(t.dof, 4);
    sum2 += t.standardised.cwiseAbs2();
    detections += t.fault_detected;
  }
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(sum2(i) / kRuns, 1.0, 0.05) << i;
  EXPECT_NEAR(detections / double(kRuns), 1e-2, 3e-3);
}

TEST(Raim, TheFaultySatelliteHasTheLargestStandardisedResidual) {
  const Eigen::MatrixXd H = geometry();
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(8);
  const Eigen::MatrixXd P = H * (H.transpose() * H).inverse() * H.transpose();
  for (int faulty = 0; faulty < 8; ++faulty) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(8);
    e(faulty) = 30.0;
    const ResidualTest t = residual_test(H, w, e - P * e, 1e-3);
    EXPECT_TRUE(t.fault_detected) << faulty;
    EXPECT_EQ(t.worst_row, faulty);
  }
  EXPECT_THROW(residual_test(H.topRows(4), w.head(4), w.head(4), 1e-3), std::invalid_argument);
}

TEST(Raim, AnInterSystemOffsetColumnCostsADegreeOfFreedom) {
  // The same geometry with its last three rows from a second system: a column of ones for
  // the offset of that system's clock.
  const Eigen::MatrixXd H4 = geometry();
  Eigen::MatrixXd H(8, 5);
  H << H4, Eigen::VectorXd::Zero(8);
  H.bottomRows(3).col(4).setOnes();
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(8);
  const Eigen::MatrixXd P = H * (H.transpose() * H).inverse() * H.transpose();
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::VectorXd sum2 = Eigen::VectorXd::Zero(8);
  int detections = 0;
  constexpr int kRuns = 20000;
  for (int k = 0; k < kRuns; ++k) {
    Eigen::VectorXd e(8);
    for (int i = 0; i < 8; ++i) e(i) = n(rng);
    const ResidualTest t = residual_test(H, w, e - P * e, 1e-2);
    EXPECT_EQ(t.dof, 3);
    sum2 += t.standardised.cwiseAbs2();
    detections += t.fault_detected;
  }
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(sum2(i) / kRuns, 1.0, 0.05) << i;
  EXPECT_NEAR(detections / double(kRuns), 1e-2, 3e-3);
  // A fault on a satellite of the second system is found as on one of the first.
  for (int faulty : {1, 6}) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(8);
    e(faulty) = 30.0;
    const ResidualTest t = residual_test(H, w, e - P * e, 1e-3);
    EXPECT_TRUE(t.fault_detected) << faulty;
    EXPECT_EQ(t.worst_row, faulty);
  }
  EXPECT_THROW(residual_test(H.topRows(5), w.head(5), w.head(5), 1e-3), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
