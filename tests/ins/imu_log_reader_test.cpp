#include "ins/imu_log_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace deepnav {
namespace {

std::string write_text(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::path(DEEPNAV_BINARY_DIR) / ("imu_log_reader_test_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path, const ImuLogOptions& o) {
  try {
    read_imu_log(path, o);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

ImuLogOptions walk_options() {
  ImuLogOptions o;
  o.format = ImuLogFormat::csv;
  o.columns = "ax,ay,az,gx,gy,gz,t";
  o.accel_unit = "g";
  o.gyro_unit = "deg/s";
  o.time_scale = 1e-3;  // millisecond ticks
  o.time_offset_s = 100.0;
  return o;
}

TEST(ImuLogReader, LoggerStyleCsvWithRepeatsCutLinesAndIrregularTicks) {
  // A cut first line, a row read twice (same values, new tick), irregular ticks, a cut last line.
  const std::string text =
      "0.011,0.038,-0.160,0.160,3326339\n"
      "0.0,0.0,1.0,0.0,0.0,10.0,1000\n"
      "0.0,0.0,1.0,0.0,0.0,20.0,1006\n"
      "0.0,0.0,1.0,0.0,0.0,20.0,1012\n"
      "0.5,0.0,1.0,0.0,0.0,30.0,1021\n"
      "0.012,-0.042,1.009,0.015,-0.084,";
  const ImuLogRead r = read_imu_log(write_text("walk.csv", text), walk_options());
  EXPECT_EQ(r.report.truncated_lines, 2);
  EXPECT_EQ(r.report.rows, 4);
  EXPECT_EQ(r.report.duplicate_rows, 1);
  EXPECT_EQ(r.report.samples, 3);
  ASSERT_EQ(r.log.samples.size(), 3u);
  EXPECT_DOUBLE_EQ(r.log.samples[0].t_s, 101.0);
  EXPECT_DOUBLE_EQ(r.log.samples[2].t_s, 101.021);
  // Rates held over the interval ending at the sample: 15 ms for the last one (the repeat dropped).
  const double g = 9.80665, d2r = M_PI / 180.0;
  EXPECT_NEAR(r.log.samples[2].dtheta_b_rad.z(), 30.0 * d2r * 0.015, 1e-12);
  EXPECT_NEAR(r.log.samples[2].dv_b_mps.x(), 0.5 * g * 0.015, 1e-12);
  EXPECT_NEAR(r.log.samples[1].dv_b_mps.z(), g * 0.006, 1e-12);
  EXPECT_NEAR(r.report.nominal_interval_s, 0.0105, 1e-12);
  EXPECT_NEAR(r.report.min_interval_s, 0.006, 1e-12);
  EXPECT_NEAR(r.report.max_interval_s, 0.015, 1e-12);
  EXPECT_TRUE(r.report.gaps.empty());
}

TEST(ImuLogReader, BackwardAndRepeatedTimesAreDroppedAndGapsListed) {
  ImuLogOptions o;
  o.format = ImuLogFormat::csv;
  o.nominal_rate_hz = 100.0;
  const std::string text =
      "t,ax,ay,az,gx,gy,gz\n"
      "0.00,0,0,-9.8,0,0,0.01\n"
      "0.01,0,0,-9.8,0,0,0.02\n"
      "0.01,0,0,-9.8,0,0,0.03\n"
      "0.005,0,0,-9.8,0,0,0.04\n"
      "0.02,0,0,-9.8,0,0,0.05\n"
      "0.50,0,0,-9.8,0,0,0.06\n"
      "0.51,0,0,-9.8,0,0,0.07\n";
  const ImuLogRead r = read_imu_log(write_text("back.csv", text), o);
  EXPECT_EQ(r.report.header_lines, 1);
  EXPECT_EQ(r.report.repeated_time, 1);
  EXPECT_EQ(r.report.backward_time, 1);
  EXPECT_EQ(r.report.first_backward_line, 5);
  EXPECT_EQ(r.report.samples, 5);
  ASSERT_EQ(r.report.gaps.size(), 1u);
  EXPECT_EQ(r.report.gaps[0].line, 7u);
  EXPECT_DOUBLE_EQ(r.report.gaps[0].t_before_s, 0.02);
  // The sample after the gap covers one nominal interval, not the gap.
  EXPECT_NEAR(r.log.samples[3].dtheta_b_rad.z(), 0.06 * 0.01, 1e-15);
}

TEST(ImuLogReader, KfGinsIncrements) {
  ImuLogOptions o;
  o.format = ImuLogFormat::kf_gins;
  o.time_offset_s = 0.5;  // a constant IMU-to-GNSS offset
  const std::string text =
      "456300.000  1e-4 2e-4 3e-4  0.01 0.02 -0.098\n"
      "456300.005\t1e-4\t2e-4\t3e-4\t0.01\t0.02\t-0.098\n";
  const ImuLogRead r = read_imu_log(write_text("kfgins.txt", text), o);
  ASSERT_EQ(r.log.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(r.log.samples[1].t_s, 456300.505);
  EXPECT_DOUBLE_EQ(r.log.samples[1].dtheta_b_rad.y(), 2e-4);
  EXPECT_DOUBLE_EQ(r.log.samples[1].dv_b_mps.z(), -0.098);
  EXPECT_EQ(r.log.form, ImuFileForm::kIncrements);
}

TEST(ImuLogReader, DeepnavCsvWithTimeOffset) {
  const std::string text =
      "# sample_rate_hz=100\n"
      "t_s,wx_radps,wy_radps,wz_radps,fx_mps2,fy_mps2,fz_mps2\n"
      "0.01,0,0,1,0,0,-9.8\n"
      "0.02,0,0,1,0,0,-9.8\n";
  ImuLogOptions o;
  o.time_offset_s = 408000.0;
  const ImuLogRead r = read_imu_log(write_text("deepnav.csv", text), o);
  ASSERT_EQ(r.log.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(r.log.samples[0].t_s, 408000.01);
  EXPECT_NEAR(r.log.samples[1].dtheta_b_rad.z(), 0.01, 1e-15);
  EXPECT_EQ(r.report.format, "deepnav");
}

TEST(ImuLogReader, MountingTurnsImuAxesIntoBodyAxes) {
  // The walk's mounting: roll 180, yaw -90. An IMU lying face up reads +1 g on its z axis at
  // rest; in body axes (z down) that is -1 g on z, and the IMU's -y axis is the body's x.
  ImuMounting m;
  m.rpy_deg = Eigen::Vector3d(180.0, 0.0, -90.0);
  ImuLog log;
  log.samples.push_back({0.01, Eigen::Vector3d(0.0, -0.01, 0.0), Eigen::Vector3d(0.0, 0.0, 0.098)});
  apply_mounting(log, m);
  EXPECT_NEAR(log.samples[0].dv_b_mps.z(), -0.098, 1e-15);
  EXPECT_NEAR(log.samples[0].dtheta_b_rad.x(), 0.01, 1e-15);
  EXPECT_NEAR(log.samples[0].dtheta_b_rad.y(), 0.0, 1e-15);
  m.imu_position_b_m = Eigen::Vector3d(0.0, 0.05, 0.0);
  EXPECT_TRUE(m.lever_arm_imu_to_antenna_b_m().isApprox(Eigen::Vector3d(0.0, -0.05, 0.0)));
}

TEST(ImuLogReader, BadFilesGiveErrorsNamingFileLineAndColumn) {
  const ImuLogOptions o = walk_options();
  const std::string good = "0,0,1,0,0,0,1000\n";
  const std::string bad_value =
      write_text("bad_value.csv", good + "0,0,1,abc,0,0,1010\n" + good + "0,0,1,0,0,0,1030\n");
  EXPECT_EQ(error_of(bad_value, o), bad_value + ":2: column 4 (gx): 'abc' is not a finite number");
  const std::string short_row = write_text("short.csv", good + "0,0,1,0,0,1010\n" + "0,0,1,0,0,0,1030\n");
  EXPECT_EQ(error_of(short_row, o), short_row + ":2: expected 7 fields (ax,ay,az,gx,gy,gz,t), found 6");
  const std::string nan = write_text("nan.csv", good + "0,0,nan,0,0,0,1010\n" + "0,0,1,0,0,0,1030\n");
  EXPECT_NE(error_of(nan, o).find(":2: column 3 (az): 'nan' is not a finite number"), std::string::npos);
  ImuLogOptions map = o;
  map.columns = "ax,ay,az,gx,gy,t";
  EXPECT_NE(error_of(bad_value, map).find("lacks gz"), std::string::npos);
  map.columns = "ax,ay,az,gx,gy,gz,time";
  EXPECT_NE(error_of(bad_value, map).find("column 7 is 'time'"), std::string::npos);
  ImuLogOptions unit = o;
  unit.accel_unit = "ft/s^2";
  EXPECT_NE(error_of(bad_value, unit).find("accelerometer unit 'ft/s^2' is not one of g, m/s^2"), std::string::npos);
  unit = o;
  unit.gyro_unit = "rad";
  EXPECT_NE(error_of(bad_value, unit).find("gyro unit 'rad' is not one of deg/s, rad/s"), std::string::npos);
  const std::string one = write_text("one.csv", good);
  EXPECT_NE(error_of(one, o).find("fewer than two IMU samples"), std::string::npos);
  EXPECT_NE(error_of("/nonexistent/imu.csv", o).find("cannot open IMU log '/nonexistent/imu.csv'"), std::string::npos);
  ImuLogOptions kf;
  kf.format = ImuLogFormat::kf_gins;
  const std::string kf_bad = write_text("kf_bad.txt", "1.0 0 0 0 0 0 0\n1.005 0 0 0 0 0\n1.010 0 0 0 0 0 0\n");
  EXPECT_NE(error_of(kf_bad, kf).find(":2: expected 7 fields"), std::string::npos);
  EXPECT_THROW(parse_imu_log_format("xsens"), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
