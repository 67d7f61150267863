// Samples beyond the configured grade's measurement range are found (the first named)
// and counted; a grade without ranges checks nothing; the shipped grades carry ranges.
#include "ins/imu_range_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace deepnav {
namespace {

/// 100 Hz samples at rest (1 g up), with `spike` applied to sample `at`.
std::vector<ImuSample> at_rest(std::size_t n, std::size_t at, const ImuSample& spike) {
  std::vector<ImuSample> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i].t_s = 0.01 * static_cast<double>(i);
    out[i].dv_b_mps = Eigen::Vector3d(0.0, 0.0, -9.80665 * 0.01);
    if (i == at) {
      out[i].dtheta_b_rad += spike.dtheta_b_rad;
      out[i].dv_b_mps += spike.dv_b_mps;
    }
  }
  return out;
}

TEST(ImuRangeCheck, FindsTheFirstSampleBeyondTheGradesRange) {
  const ImuGrade tactical = load_imu_grade(std::string(DEEPNAV_SOURCE_DIR) + "/data/imu_grades.yaml", "tactical");
  ImuSample spin;
  spin.dtheta_b_rad = Eigen::Vector3d(0.0, -1500.0 * M_PI / 180.0 * 0.01, 0.0);  // 1500 deg/s on y
  const ImuRangeExcess found = samples_beyond_range(at_rest(200, 50, spin), tactical.model);
  EXPECT_EQ(found.samples, 1u);
  ASSERT_TRUE(found.first_t_s.has_value());
  EXPECT_NEAR(*found.first_t_s, 0.5, 1e-12);
  EXPECT_NE(found.first_what.find("gyro 1500 deg/s"), std::string::npos) << found.first_what;
  EXPECT_NE(found.first_what.find("1000"), std::string::npos) << found.first_what;

  ImuSample shock;
  shock.dv_b_mps = Eigen::Vector3d(60.0 * 9.80665 * 0.01, 0.0, 0.0);  // 60 g
  EXPECT_EQ(samples_beyond_range(at_rest(200, 10, shock), tactical.model).samples, 1u);
  EXPECT_EQ(samples_beyond_range(at_rest(200, 10, ImuSample{}), tactical.model).samples, 0u);
}

TEST(ImuRangeCheck, AGradeWithoutRangesChecksNothing) {
  const ImuGrade paper = load_imu_grade(std::string(DEEPNAV_SOURCE_DIR) + "/data/imu_grades.yaml", "paper003");
  EXPECT_EQ(paper.model.gyro.full_scale, 0.0);
  ImuSample spin;
  spin.dtheta_b_rad = Eigen::Vector3d(0.0, 0.0, 50.0);  // 5000 rad/s
  EXPECT_EQ(samples_beyond_range(at_rest(20, 5, spin), paper.model).samples, 0u);
}

TEST(ImuRangeCheck, ShippedGradesCarryTheirRanges) {
  const std::string path = std::string(DEEPNAV_SOURCE_DIR) + "/data/imu_grades.yaml";
  for (const char* name : {"consumer-mems", "industrial-mems", "tactical", "navigation"}) {
    const ImuGrade g = load_imu_grade(path, name);
    EXPECT_GE(g.model.gyro.full_scale, 400.0 * M_PI / 180.0) << name;
    EXPECT_GE(g.model.accel.full_scale, 8.0 * 9.80665) << name;
  }
}

}  // namespace
}  // namespace deepnav
