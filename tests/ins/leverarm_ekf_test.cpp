#include "ins/leverarm_ekf.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "ins/lever_arm_imu_sim.hpp"
#include "ins/ship_roll_model.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kG = 9.80665;

double max_roll_error_deg(const LeverArmEkfRun& run, const std::vector<AttitudeTruth>& truth, double t0, double t1) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (truth[i].t_s >= t0 && truth[i].t_s <= t1)
      worst = std::max(worst, std::abs(std::remainder(run.roll_rad[i] - truth[i].roll_rad, 2 * std::numbers::pi)));
  return worst / kDeg;
}

TEST(ShipRollModel, RollStartsWithTheMomentAndRatesAreConsistent) {
  const auto truth = simulate_ship_roll({});
  ASSERT_EQ(truth.size(), 2001u);
  double peak = 0.0;
  for (const auto& s : truth) {
    if (s.t_s < 5.0) {
      EXPECT_EQ(s.roll_rad, 0.0);
    }
    peak = std::max(peak, std::abs(s.roll_rad));
  }
  EXPECT_GT(peak, 8.0 * kDeg);
  EXPECT_LT(peak, 15.0 * kDeg);
  // The stored angular acceleration is the derivative of the stored rate.
  for (std::size_t i = 600; i < 1400; i += 97) {
    const double fd = (truth[i + 1].w_nb_b_radps.x() - truth[i - 1].w_nb_b_radps.x()) / 0.02;
    EXPECT_NEAR(truth[i].dw_nb_b_radps2.x(), fd, 2e-3);
  }
}

TEST(ShipRollModel, EulerOscillationRatesMatchAttitudeDerivative) {
  EulerOscillationParameters p;
  p.amplitude_rad = Eigen::Vector3d(10, 6, 8) * kDeg;
  p.period_s = Eigen::Vector3d(3.1, 4.3, 5.7);
  p.duration_s = 5.0;
  p.sample_rate_hz = 1000.0;
  const auto truth = simulate_euler_oscillation(p);
  for (std::size_t i = 100; i + 1 < truth.size(); i += 700) {
    // C' = C [w x]  =>  w from the finite-difference derivative of C.
    const Eigen::Matrix3d dC = (truth[i + 1].C_b_n - truth[i - 1].C_b_n) / 0.002;
    const Eigen::Matrix3d W = truth[i].C_b_n.transpose() * dC;
    EXPECT_NEAR(W(2, 1), truth[i].w_nb_b_radps.x(), 1e-4);
    EXPECT_NEAR(W(0, 2), truth[i].w_nb_b_radps.y(), 1e-4);
    EXPECT_NEAR(W(1, 0), truth[i].w_nb_b_radps.z(), 1e-4);
    const Eigen::Vector3d dw_fd = (truth[i + 1].w_nb_b_radps - truth[i - 1].w_nb_b_radps) / 0.002;
    EXPECT_LT((dw_fd - truth[i].dw_nb_b_radps2).norm(), 1e-4);
  }
}

TEST(LeverArmEkf, SmoothedAngularAccelerationOfASine) {
  std::vector<Eigen::Vector3d> w;
  const double dt = 0.01;
  for (int i = 0; i < 400; ++i) w.emplace_back(std::sin(2.0 * i * dt), 0.0, 0.5);
  const auto dw = smoothed_angular_acceleration(w, dt, 5);
  for (int i = 10; i < 390; i += 37) {
    EXPECT_NEAR(dw[i].x(), 2.0 * std::cos(2.0 * i * dt), 0.01);
    EXPECT_NEAR(dw[i].z(), 0.0, 1e-9);
  }
}

// Paper 004 [docs/references.md] Table 1: the conventional filter's roll error grows with the arm; the
// lever-arm filter's stays flat and below it; the arm itself is recovered.
TEST(LeverArmEkf, ShipScenarioReproducesPaperFinding) {
  const auto truth = simulate_ship_roll({});
  const MemsImuFigures imu = MemsImuFigures::industrial();
  std::vector<double> conventional, proposed;
  for (double arm : {0.25, 0.5, 0.75, 1.0}) {
    double conv = 0.0, prop = 0.0;
    constexpr int kRuns = 4;
    for (int r = 0; r < kRuns; ++r) {
      std::mt19937_64 rng(7000 + r);
      const auto readings = simulate_lever_arm_imu(truth, {0.0, 0.0, -arm}, imu, kG, rng);  // above the CG: -z
      const auto c = run_lever_arm_ekf(readings, paper004_config(LeverArmModel::kNone, imu));
      const auto p = run_lever_arm_ekf(readings, paper004_config(LeverArmModel::kVertical, imu));
      conv += max_roll_error_deg(c, truth, 10.0, 12.0) / kRuns;
      prop += max_roll_error_deg(p, truth, 10.0, 12.0) / kRuns;
      EXPECT_NEAR(p.lever_b_m.back().z(), -arm, 0.03) << "arm " << arm << " run " << r;
      EXPECT_LT(p.final_lever_sigma_m.z(), 0.1);  // R is conservative (1 m/s^2), so sigma is too
    }
    conventional.push_back(conv);
    proposed.push_back(prop);
  }
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_LT(proposed[k], conventional[k]) << k;
    if (k > 0) {
      EXPECT_GT(conventional[k], conventional[k - 1] + 0.02) << k;
    }
  }
  const auto [lo, hi] = std::minmax_element(proposed.begin(), proposed.end());
  EXPECT_LT(*hi, 1.15 * *lo);                         // flat across arms
  EXPECT_GT(conventional[3], 1.8 * conventional[0]);  // paper: +97 % from 0.25 m to 1 m
  EXPECT_LT(*hi, conventional[0]);                    // below the conventional filter's smallest error
}

TEST(LeverArmEkf, RateTableWithEighteenCentimetreArm) {
  const auto truth = simulate_rate_table({});
  const MemsImuFigures imu = MemsImuFigures::industrial();
  std::mt19937_64 rng(99);
  const auto readings = simulate_lever_arm_imu(truth, {0.0, 0.0, -0.18}, imu, kG, rng);
  const auto c = run_lever_arm_ekf(readings, paper004_config(LeverArmModel::kNone, imu));
  const auto p = run_lever_arm_ekf(readings, paper004_config(LeverArmModel::kVertical, imu));
  const double conv = max_roll_error_deg(c, truth, 8.0, 20.0);
  const double prop = max_roll_error_deg(p, truth, 8.0, 20.0);
  EXPECT_LT(prop, 0.5 * conv) << "conventional " << conv << " deg, lever-arm " << prop << " deg";
  EXPECT_NEAR(p.lever_b_m.back().z(), -0.18, 0.01);
}

TEST(LeverArmEkf, FullLeverArmUnderRichMotionAndUnobservableUnderPureRoll) {
  const MemsImuFigures imu = MemsImuFigures::industrial();
  const Eigen::Vector3d arm(0.3, -0.2, -0.5);
  EulerOscillationParameters motion;
  motion.amplitude_rad = Eigen::Vector3d(15, 10, 20) * kDeg;
  motion.period_s = Eigen::Vector3d(3.1, 4.3, 5.7);
  motion.phase_rad = Eigen::Vector3d(0.0, 0.5, 1.0);
  motion.duration_s = 60.0;
  const auto rich = simulate_euler_oscillation(motion);
  std::mt19937_64 rng(5);
  const auto rich_run =
      run_lever_arm_ekf(simulate_lever_arm_imu(rich, arm, imu, kG, rng), paper004_config(LeverArmModel::kFull3d, imu));
  EXPECT_TRUE(rich_run.observability.fully_observable) << rich_run.observability.summary;
  EXPECT_LT((rich_run.lever_b_m.back() - arm).norm(), 0.05) << rich_run.lever_b_m.back().transpose();

  const auto roll_only = simulate_ship_roll({});
  const auto roll_run = run_lever_arm_ekf(simulate_lever_arm_imu(roll_only, arm, imu, kG, rng),
                                          paper004_config(LeverArmModel::kFull3d, imu));
  ASSERT_FALSE(roll_run.observability.fully_observable);
  // The unobservable direction is the roll axis, body x.
  EXPECT_GT(std::abs(roll_run.observability.directions.col(0).x()), 0.99);
  EXPECT_EQ(roll_run.observability.summary.find("not observable along body direction [1.00"), 0u)
      << roll_run.observability.summary;
  EXPECT_GT(roll_run.final_lever_sigma_m.x(), 0.5);           // the filter never learns it: prior stays
  EXPECT_NEAR(roll_run.lever_b_m.back().z(), arm.z(), 0.05);  // the others it does
  EXPECT_NEAR(roll_run.lever_b_m.back().y(), arm.y(), 0.05);
}

TEST(LeverArmEkf, ObservabilityVerdicts) {
  // Information only about y and z (rotation about x): x is structurally unobservable.
  const auto none_x = assess_lever_arm_observability(Eigen::Vector3d(0.0, 1e4, 1e4).asDiagonal(), 0.05);
  EXPECT_FALSE(none_x.fully_observable);
  EXPECT_EQ(none_x.summary.find("not observable along body direction [1.00, 0.00, 0.00]"), 0u) << none_x.summary;
  // Every direction seen, one too weakly: "weakly observable", not "not observable".
  const auto weak = assess_lever_arm_observability(Eigen::Vector3d(1e4, 1e4, 1e3).asDiagonal(), 0.02);
  EXPECT_FALSE(weak.fully_observable);
  EXPECT_EQ(weak.summary.find("weakly observable"), 0u) << weak.summary;
  const auto all = assess_lever_arm_observability(Eigen::Vector3d(1e4, 2e4, 3e4).asDiagonal(), 0.05);
  EXPECT_TRUE(all.fully_observable) << all.summary;
  EXPECT_NEAR(all.sigma_m(0), 0.01, 1e-12);
}

TEST(LeverArmEkf, BadInputIsRejected) {
  const MemsImuFigures imu = MemsImuFigures::industrial();
  LeverArmEkfConfig config = paper004_config(LeverArmModel::kVertical, imu);
  LeverArmEkf ekf(config, Eigen::Quaterniond::Identity());
  EXPECT_THROW(ekf.update(Eigen::Vector3d(0, 0, std::nan("")), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(ekf.propagate(Eigen::Vector3d::Zero(), 0.0), std::invalid_argument);
  config.accel_sigma_mps2 = 0.0;
  EXPECT_THROW(LeverArmEkf(config, Eigen::Quaterniond::Identity()), std::invalid_argument);
  EXPECT_THROW(run_lever_arm_ekf({}, paper004_config(LeverArmModel::kNone, imu)), std::invalid_argument);
  ShipRollParameters ship;
  ship.roll_inertia_kgm2 = 0.0;
  EXPECT_THROW(simulate_ship_roll(ship), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
