#include "ins/imu_model.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "ins/sim/imu_error_generator.hpp"

namespace deepnav {
namespace {

const std::string kGradesPath = std::string(DEEPNAV_SOURCE_DIR) + "/data/imu_grades.yaml";

std::string write_temp_yaml(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(DEEPNAV_BINARY_DIR) / ("imu_model_test_" + name + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& path) {
  try {
    load_imu_grades(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ImuGrades, ShippedFileHasAllGradesOrderedByQuality) {
  const auto grades = load_imu_grades(kGradesPath);
  ASSERT_EQ(grades.size(), 5u);
  const char* names[] = {"consumer-mems", "industrial-mems", "tactical", "navigation"};
  double previous_bias = 1e9;
  for (const char* name : names) {
    const auto g = load_imu_grade(kGradesPath, name);
    EXPECT_FALSE(g.description.empty()) << name;
    EXPECT_GT(g.model.sample_rate_hz, 0.0);
    EXPECT_LT(g.model.gyro.bias_sigma, previous_bias) << name << " should be better than the grade before it";
    previous_bias = g.model.gyro.bias_sigma;
  }
}

TEST(ImuGrades, Paper003PresetConvertsToSi) {
  const auto g = load_imu_grade(kGradesPath, "paper003");
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(g.model.accel.bias[i], 100e-6 * 9.80665, 1e-12);
    EXPECT_NEAR(g.model.gyro.bias[i], 0.1 * M_PI / 180.0 / 3600.0, 1e-15);
  }
  EXPECT_EQ(g.model.gyro.random_walk, 0.0);
}

TEST(ImuGrades, TacticalArwConvertsFromDegPerSqrtHour) {
  const auto g = load_imu_grade(kGradesPath, "tactical");
  EXPECT_NEAR(g.model.gyro.random_walk, 0.125 * M_PI / 180.0 / 60.0, 1e-15);
  EXPECT_NEAR(g.model.accel.random_walk, 0.03 / 60.0, 1e-15);
  EXPECT_NEAR(g.model.gyro.scale_factor_sigma, 150e-6, 1e-15);
}

TEST(ImuGrades, UnknownGradeListsAvailableNames) {
  try {
    load_imu_grade(kGradesPath, "space-grade");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("space-grade"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("tactical"), std::string::npos);
  }
}

const std::string kGyroOk =
    "    gyro: {bias_sigma_deg_per_h: 1, bias_instability_deg_per_h: 0, correlation_time_s: 0,"
    " arw_deg_per_sqrt_h: 0.1, scale_factor_ppm: 1, misalignment_mrad: 0, quantization_rad: 0}\n";

TEST(ImuGrades, ADocumentThatIsNoMapIsRejectedNamingTheFile) {
  // A scalar at the top (what a UTF-16 reading of stray bytes gives) made yaml-cpp throw
  // "operator[] call on a scalar", naming no file.
  for (const char* text : {"just text\n", "[1, 2]\n", ""}) {
    const auto path = write_temp_yaml("scalar", text);
    EXPECT_EQ(error_of(path), path + ": expected a top-level map 'grades' of named IMU grades") << text;
  }
}

TEST(ImuGrades, AliasesThatMultiplyAreRejected) {
  std::string laughs = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 11; ++level) {
    laughs += fmt::format("a{}: &a{} [", level, level);
    for (int k = 0; k < 10; ++k) laughs += fmt::format("{}*a{}", k ? ", " : "", level - 1);
    laughs += "]\n";
  }
  const auto path = write_temp_yaml("laughs", laughs);
  EXPECT_EQ(error_of(path), path +
                                ":5: the aliases repeat more than 100000 nodes (alias '*a3' alone repeats 11111): "
                                "nested aliases that multiply are refused");
}

TEST(ImuGrades, MissingFieldIsNamed) {
  const auto path =
      write_temp_yaml("missing", "grades:\n  g1:\n    sample_rate_hz: 100\n" + kGyroOk +
                                     "    accel: {bias_sigma_ug: 1, bias_instability_ug: 0, correlation_time_s: 0,"
                                     " scale_factor_ppm: 1, misalignment_mrad: 0, quantization_mps: 0}\n");
  const auto msg = error_of(path);
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("g1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("accel.vrw_mps_per_sqrt_h"), std::string::npos) << msg;
}

TEST(ImuGrades, MisspelledFieldIsRejected) {
  const auto path =
      write_temp_yaml("typo", "grades:\n  g1:\n    sample_rate_hz: 100\n" + kGyroOk + "    accel: {vrw_m_per_s: 1}\n");
  EXPECT_NE(error_of(path).find("accel.vrw_m_per_s"), std::string::npos) << error_of(path);
}

// The same class of input the scenario fuzzer found (a key that is a list): it escaped as
// yaml-cpp's "bad conversion", without the file or the field.
TEST(ImuGrades, KeyThatIsAListIsRejected) {
  const auto path =
      write_temp_yaml("list_key", "grades:\n  g1:\n    sample_rate_hz: 100\n" + kGyroOk + "    accel: {[a, b]: 1}\n");
  const std::string error = error_of(path);
  EXPECT_NE(error.find("imu_model_test_list_key.yaml: grade 'g1', field 'accel.'"), std::string::npos) << error;
  EXPECT_NE(error.find("expected field names as keys"), std::string::npos) << error;
}

TEST(ImuGrades, NegativeAndNonNumericValuesAreRejected) {
  auto path = write_temp_yaml("negative", "grades:\n  g1:\n    sample_rate_hz: -5\n");
  EXPECT_NE(error_of(path).find("sample_rate_hz"), std::string::npos);
  path = write_temp_yaml("text", "grades:\n  g1:\n    sample_rate_hz: fast\n");
  EXPECT_NE(error_of(path).find("expected a number"), std::string::npos) << error_of(path);
  EXPECT_NE(error_of("/nonexistent/grades.yaml").find("cannot open"), std::string::npos);
}

ImuErrorModel only_gyro(const TriadErrorSpec& s) {
  ImuErrorModel m;
  m.gyro = s;
  return m;
}

TEST(ImuErrorGenerator, ConstantBiasAddsBiasTimesInterval) {
  TriadErrorSpec s;
  s.bias = Eigen::Vector3d(1e-4, -2e-4, 3e-4);
  ImuErrorGenerator gen(only_gyro(s), 1);
  Eigen::Vector3d dth(0.01, 0.02, 0.03), dv(1, 2, 3);
  gen.apply(0.01, dth, dv);
  EXPECT_NEAR((dth - Eigen::Vector3d(0.01, 0.02, 0.03) - s.bias * 0.01).norm(), 0.0, 1e-16);
  EXPECT_EQ(dv, Eigen::Vector3d(1, 2, 3));  // accelerometers error-free
}

TEST(ImuErrorGenerator, SameSeedSameErrorsOtherSeedOther) {
  const auto model = load_imu_grade(kGradesPath, "consumer-mems").model;
  ImuErrorGenerator a(model, 42), b(model, 42), c(model, 43);
  Eigen::Vector3d x1 = Eigen::Vector3d::Zero(), v1 = x1, x2 = x1, v2 = x1, x3 = x1, v3 = x1;
  a.apply(0.01, x1, v1);
  b.apply(0.01, x2, v2);
  c.apply(0.01, x3, v3);
  EXPECT_EQ(x1, x2);
  EXPECT_EQ(v1, v2);
  EXPECT_NE(x1, x3);
}

TEST(ImuErrorGenerator, AngleRandomWalkGrowsWithSquareRootOfTime) {
  TriadErrorSpec s;
  s.random_walk = 0.1 * imu_units::kDegPerSqrtHour_to_radpsqrts;
  const double dt = 0.1;
  const int runs = 300, n1 = 1000, n2 = 4000;  // 100 s and 400 s
  double sum_sq_100 = 0.0, sum_sq_400 = 0.0;
  for (int r = 0; r < runs; ++r) {
    ImuErrorGenerator gen(only_gyro(s), 1000 + r);
    Eigen::Vector3d angle = Eigen::Vector3d::Zero();
    for (int k = 1; k <= n2; ++k) {
      Eigen::Vector3d dth = Eigen::Vector3d::Zero(), dv = dth;
      gen.apply(dt, dth, dv);
      angle += dth;
      if (k == n1) sum_sq_100 += angle.squaredNorm();
    }
    sum_sq_400 += angle.squaredNorm();
  }
  const double sigma_100 = std::sqrt(sum_sq_100 / (3 * runs));
  const double sigma_400 = std::sqrt(sum_sq_400 / (3 * runs));
  // 900 samples: the sample sigma is within ~5 % (2.4 standard errors at 7 %).
  EXPECT_NEAR(sigma_100 / (s.random_walk * std::sqrt(100.0)), 1.0, 0.07);
  EXPECT_NEAR(sigma_400 / (s.random_walk * std::sqrt(400.0)), 1.0, 0.07);
}

TEST(ImuErrorGenerator, GaussMarkovBiasHasStatedSigmaAndCorrelationTime) {
  TriadErrorSpec s;
  s.bias_instability_sigma = 1e-5;
  s.bias_correlation_time_s = 10.0;
  ImuErrorGenerator gen(only_gyro(s), 7);
  const int n = 200000, lag = 10;  // dt = 1 s, lag = one correlation time
  std::vector<double> b(n);
  for (int k = 0; k < n; ++k) {
    Eigen::Vector3d dth = Eigen::Vector3d::Zero(), dv = dth;
    b[k] = gen.gyro_bias_radps().x();
    gen.apply(1.0, dth, dv);
  }
  double var = 0.0, cov = 0.0;
  for (int k = 0; k < n; ++k) var += b[k] * b[k];
  for (int k = 0; k + lag < n; ++k) cov += b[k] * b[k + lag];
  var /= n;
  cov /= (n - lag);
  EXPECT_NEAR(std::sqrt(var) / s.bias_instability_sigma, 1.0, 0.05);
  EXPECT_NEAR(cov / var, std::exp(-1.0), 0.05);
}

TEST(ImuErrorGenerator, QuantizationKeepsOutputsOnLsbAndSumWithinOneLsb) {
  ImuErrorModel m;
  m.accel.quantization = 1e-3;
  ImuErrorGenerator gen(m, 3);
  Eigen::Vector3d true_sum = Eigen::Vector3d::Zero(), out_sum = true_sum;
  for (int k = 0; k < 1000; ++k) {
    Eigen::Vector3d dth = Eigen::Vector3d::Zero();
    Eigen::Vector3d dv(0.000377 * (k % 7), -0.0123, 0.98e-4);
    true_sum += dv;
    gen.apply(0.01, dth, dv);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(dv[i] / 1e-3, std::round(dv[i] / 1e-3), 1e-9);
    out_sum += dv;
  }
  EXPECT_LE((out_sum - true_sum).cwiseAbs().maxCoeff(), 0.5e-3 + 1e-12);
}

TEST(ImuErrorGenerator, ScaleFactorAndMisalignmentAreDrawnWithStatedSigma) {
  TriadErrorSpec s;
  s.scale_factor_sigma = 1e-3;
  s.misalignment_sigma_rad = 2e-3;
  double sf_sq = 0.0, mis_sq = 0.0;
  const int runs = 400;
  for (int r = 0; r < runs; ++r) {
    ImuErrorGenerator gen(only_gyro(s), 500 + r);
    sf_sq += gen.gyro_draw().scale_factor.squaredNorm();
    mis_sq += gen.gyro_draw().misalignment.squaredNorm();
    EXPECT_EQ(gen.gyro_draw().misalignment.diagonal(), Eigen::Vector3d::Zero());
    // The increment really passes through (I + S + M).
    Eigen::Vector3d dth(1.0, 0.0, 0.0), dv = Eigen::Vector3d::Zero();
    gen.apply(0.01, dth, dv);
    EXPECT_NEAR(dth.x(), 1.0 + gen.gyro_draw().scale_factor.x(), 1e-15);
    EXPECT_NEAR(dth.y(), gen.gyro_draw().misalignment(1, 0), 1e-15);
  }
  EXPECT_NEAR(std::sqrt(sf_sq / (3 * runs)) / 1e-3, 1.0, 0.08);
  EXPECT_NEAR(std::sqrt(mis_sq / (6 * runs)) / 2e-3, 1.0, 0.08);
}

}  // namespace
}  // namespace deepnav
