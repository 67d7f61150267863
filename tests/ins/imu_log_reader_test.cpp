#include "ins/imu_log_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

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
  // A cut first line, a row repeating the previous one's values at a new tick (data: kept),
  // irregular ticks, a cut last line.
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
  EXPECT_EQ(r.report.repeated_values, 1);
  EXPECT_EQ(r.report.duplicate_rows, 0);
  EXPECT_EQ(r.report.samples, 4);
  ASSERT_EQ(r.log.samples.size(), 4u);
  EXPECT_DOUBLE_EQ(r.log.samples[0].t_s, 101.0);
  EXPECT_DOUBLE_EQ(r.log.samples[3].t_s, 101.021);
  // Rates held over the interval ending at the sample: the repeat's 6 ms, the last one's 9 ms.
  const double g = 9.80665, d2r = M_PI / 180.0;
  EXPECT_NEAR(r.log.samples[2].dtheta_b_rad.z(), 20.0 * d2r * 0.006, 1e-12);
  EXPECT_NEAR(r.log.samples[3].dtheta_b_rad.z(), 30.0 * d2r * 0.009, 1e-12);
  EXPECT_NEAR(r.log.samples[3].dv_b_mps.x(), 0.5 * g * 0.009, 1e-12);
  EXPECT_NEAR(r.log.samples[1].dv_b_mps.z(), g * 0.006, 1e-12);
  EXPECT_NEAR(r.report.nominal_interval_s, 0.007, 1e-12);
  EXPECT_NEAR(r.report.min_interval_s, 0.006, 1e-12);
  EXPECT_NEAR(r.report.max_interval_s, 0.009, 1e-12);
  EXPECT_TRUE(r.report.gaps.empty());
  EXPECT_TRUE(r.report.warnings.empty());
}

TEST(ImuLogReader, EqualValuesAtNewTimesAreData) {
  // A still IMU without noise (a simulator's) writes the same increments at every time: each
  // row is a sample, none lost, no gap.
  ImuLogOptions o;
  o.format = ImuLogFormat::csv;
  o.columns = "t,gx,gy,gz,ax,ay,az";
  o.quantity = ImuQuantity::increments;
  o.accel_unit = "m/s";
  o.gyro_unit = "rad";
  std::string text;
  for (int k = 1; k <= 100; ++k) text += std::to_string(0.01 * k) + ",5.78e-07,0,-4.45e-07,0,0,-0.0980665\n";
  const ImuLogRead r = read_imu_log(write_text("still.csv", text), o);
  EXPECT_EQ(r.report.samples, 100);
  EXPECT_EQ(r.report.repeated_values, 99);
  EXPECT_TRUE(r.report.gaps.empty());
  double dv = 0.0;
  for (const ImuSample& s : r.log.samples) dv += s.dv_b_mps.z();
  EXPECT_NEAR(dv, -9.80665, 1e-9);  // one second of gravity's increments, whole
}

TEST(ImuLogReader, RepeatedTimesAreDroppedWithAWarningAndGapsListed) {
  ImuLogOptions o;
  o.format = ImuLogFormat::csv;
  o.nominal_rate_hz = 100.0;
  const std::string text =
      "t,ax,ay,az,gx,gy,gz\n"
      "0.00,0,0,-9.8,0,0,0.01\n"
      "0.01,0,0,-9.8,0,0,0.02\n"
      "0.01,0,0,-9.8,0,0,0.02\n"
      "0.01,0,0,-9.8,0,0,0.03\n"
      "0.02,0,0,-9.8,0,0,0.05\n"
      "0.50,0,0,-9.8,0,0,0.06\n"
      "0.51,0,0,-9.8,0,0,0.07\n";
  const std::string path = write_text("repeat.csv", text);
  const ImuLogRead r = read_imu_log(path, o);
  EXPECT_EQ(r.report.header_lines, 1);
  EXPECT_EQ(r.report.duplicate_rows, 1);  // the row written twice
  EXPECT_EQ(r.report.repeated_time, 1);   // another sample at the same time
  EXPECT_EQ(r.report.samples, 5);
  ASSERT_EQ(r.report.warnings.size(), 2u);
  EXPECT_EQ(r.report.warnings[0],
            path + ":4: 1 row(s) repeat the row before them, time and values: dropped (written twice)");
  EXPECT_NE(r.report.warnings[1].find(path + ":5: 1 row(s) at the time of the row before them with other values: "
                                             "dropped"),
            std::string::npos);
  ASSERT_EQ(r.report.gaps.size(), 1u);
  EXPECT_EQ(r.report.gaps[0].line, 7u);
  EXPECT_DOUBLE_EQ(r.report.gaps[0].t_before_s, 0.02);
  // The sample after the gap covers one nominal interval, not the gap.
  EXPECT_NEAR(r.log.samples[3].dtheta_b_rad.z(), 0.06 * 0.01, 1e-15);
}

TEST(ImuLogReader, TimeGoingBackIsAnErrorNamingBothLines) {
  // Two rows swapped (or a logger's clock re-set): the log's order cannot be trusted.
  ImuLogOptions o;
  o.format = ImuLogFormat::csv;
  const std::string text =
      "0.00,0,0,-9.8,0,0,0.01\n"
      "0.02,0,0,-9.8,0,0,0.02\n"
      "0.01,0,0,-9.8,0,0,0.03\n"
      "0.03,0,0,-9.8,0,0,0.04\n";
  const std::string path = write_text("swapped.csv", text);
  EXPECT_EQ(error_of(path, o), path +
                                   ":3: time 0.01 goes back before line 2's: the log's times must increase (rows out "
                                   "of order, or the logger's clock re-set)");
  ImuLogOptions kf;
  kf.format = ImuLogFormat::kf_gins;
  const std::string kf_path = write_text("kf_back.txt", "1.0 0 0 0 0 0 0\n1.01 0 0 0 0 0 0\n0.5 0 0 0 0 0 0\n");
  EXPECT_NE(error_of(kf_path, kf).find(kf_path + ":3: time 0.5 goes back before line 2's"), std::string::npos);
}

TEST(ImuLogReader, ReadsFromAStream) {
  ImuLogOptions o = walk_options();
  std::istringstream in("0,0,1,0,0,0,1000\n0,0,1,0,0,0,1010\n0,0,1,0,0,0,1020\n");
  const ImuLogRead r = read_imu_log(in, "stream.csv", o);
  EXPECT_EQ(r.report.samples, 3);
  EXPECT_EQ(r.log.source, "stream.csv");
  o.format = ImuLogFormat::deepnav;
  std::istringstream again("");
  EXPECT_THROW(read_imu_log(again, "stream.csv", o), std::invalid_argument);
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
