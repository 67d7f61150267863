#include "ins/imu_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ins/sim/simulated_imu_file.hpp"
#include "ins_test_trajectories.hpp"

namespace deepnav {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(DEEPNAV_BINARY_DIR) / ("imu_file_test_" + name)).string();
}

std::string write_text(const std::string& name, const std::string& text) {
  const auto path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string read_error(const std::string& path) {
  try {
    read_imu_csv(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

const std::string kHeader = "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps\n";

TEST(ImuFile, SimulatedFileRoundTripsExactlyAndIsReproducible) {
  const wgs84::Llh llh{0.6, 2.2, 50.0};
  test::ConingTrajectory traj(llh, 3.0, 0.05, 1.0);
  ImuSimConfig cfg;
  cfg.imu.sample_rate_hz = 200.0;
  cfg.imu.gyro.random_walk = 1e-4;
  const auto path_a = temp_path("a.csv"), path_b = temp_path("b.csv");
  write_simulated_imu_csv(path_a, traj, cfg, 9);
  write_simulated_imu_csv(path_b, traj, cfg, 9);
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(path_a).parent_path()))
    EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  const auto slurp = [](const std::string& p) {
    std::stringstream ss;
    ss << std::ifstream(p).rdbuf();
    return ss.str();
  };
  EXPECT_EQ(slurp(path_a), slurp(path_b));

  const ImuLog log = read_imu_csv(path_a);
  const auto expected = simulate_imu(traj, cfg, 9);
  ASSERT_EQ(log.samples.size(), expected.size());
  EXPECT_EQ(log.form, ImuFileForm::kIncrements);
  EXPECT_DOUBLE_EQ(log.nominal_interval_s, 1.0 / 200.0);
  EXPECT_TRUE(log.gaps.empty());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(log.samples[k].t_s, expected[k].t_s);
    EXPECT_EQ(log.samples[k].dtheta_b_rad, expected[k].dtheta_b_rad);
    EXPECT_EQ(log.samples[k].dv_b_mps, expected[k].dv_b_mps);
  }
}

TEST(ImuFile, RateFormConvertsToIncrements) {
  std::vector<ImuSample> samples;
  for (int k = 1; k <= 10; ++k) {
    samples.push_back({k * 0.01, Eigen::Vector3d(1e-4, 2e-4, 3e-4) * k, Eigen::Vector3d(0.01, -0.02, -0.098)});
  }
  const auto path = temp_path("rates.csv");
  write_imu_csv(path, samples, ImuFileForm::kRates, 100.0);
  const ImuLog log = read_imu_csv(path);
  EXPECT_EQ(log.form, ImuFileForm::kRates);
  ASSERT_EQ(log.samples.size(), samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    EXPECT_NEAR((log.samples[k].dtheta_b_rad - samples[k].dtheta_b_rad).norm(), 0.0, 1e-15);
    EXPECT_NEAR((log.samples[k].dv_b_mps - samples[k].dv_b_mps).norm(), 0.0, 1e-15);
  }
}

TEST(ImuFile, GapsAreReportedNotInterpolated) {
  const auto path = write_text("gap.csv",
                               "t_s,wx_radps,wy_radps,wz_radps,fx_mps2,fy_mps2,fz_mps2\n"
                               "0.01,1,0,0,0,0,-9.8\n0.02,1,0,0,0,0,-9.8\n0.03,1,0,0,0,0,-9.8\n"
                               "0.50,1,0,0,0,0,-9.8\n0.51,1,0,0,0,0,-9.8\n");
  const ImuLog log = read_imu_csv(path);
  EXPECT_NEAR(log.nominal_interval_s, 0.01, 1e-12);  // median without a rate comment
  ASSERT_EQ(log.gaps.size(), 1u);
  EXPECT_EQ(log.gaps[0].line, 5u);
  EXPECT_DOUBLE_EQ(log.gaps[0].t_before_s, 0.03);
  EXPECT_DOUBLE_EQ(log.gaps[0].t_after_s, 0.50);
  // The sample after the gap covers one nominal interval, not the 0.47 s hole.
  EXPECT_NEAR(log.samples[3].dtheta_b_rad.x(), 0.01, 1e-12);
}

TEST(ImuFile, BadInputNamesTheLine) {
  struct Case {
    const char* name;
    std::string text;
    const char* line;
    const char* words;
  };
  const std::vector<Case> cases = {
      {"nan", kHeader + "0.01,0,0,0,0,0,-0.098\n0.02,0,nan,0,0,0,-0.098\n", ":3:", "dtheta_y_rad"},
      {"inf", kHeader + "0.01,0,0,0,0,0,inf\n", ":2:", "finite"},
      {"duplicate", kHeader + "0.01,0,0,0,0,0,0\n0.02,0,0,0,0,0,0\n0.02,0,0,0,0,0,0\n", ":4:", "duplicate"},
      {"backwards", kHeader + "0.01,0,0,0,0,0,0\n0.03,0,0,0,0,0,0\n0.02,0,0,0,0,0,0\n", ":4:", "non-monotonic"},
      {"columns", kHeader + "0.01,0,0,0,0,0\n", ":2:", "expected 7"},
      {"text", kHeader + "0.01,0,0,zero,0,0,0\n", ":2:", "not a number"},
      {"units", "t_s,dtheta_x_deg,dtheta_y_deg,dtheta_z_deg,dv_x_mps,dv_y_mps,dv_z_mps\n0.01,0,0,0,0,0,0\n",
       ":1:", "expected 't_s,dtheta_x_rad"},
      {"blank", kHeader + "0.01,0,0,0,0,0,0\n\n0.02,0,0,0,0,0,0\n", ":3:", "empty line"},
      {"rate", "# sample_rate_hz=-1\n" + kHeader, ":1:", "sample_rate_hz"},
  };
  for (const auto& c : cases) {
    const auto path = write_text(std::string(c.name) + ".csv", c.text);
    const std::string msg = read_error(path);
    EXPECT_NE(msg.find(path + c.line), std::string::npos) << c.name << ": " << msg;
    EXPECT_NE(msg.find(c.words), std::string::npos) << c.name << ": " << msg;
  }
  EXPECT_NE(read_error(temp_path("missing.csv")).find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace deepnav

namespace deepnav {
namespace {

TEST(ImuFile, SamplesBeyondAnySensorsRangeAreErrors) {
  // One increment of dv = 1e100 m/s (or 1e8) in 10 ms: no accelerometer measures that; the
  // sample once drove the aided filter to "valid" fixes 1e8 m up, or to a failure that named
  // no file. The error names the file, line and column.
  const std::string rows = "# sample_rate_hz=100\n" + kHeader + "0.01,0,0,0,0,0,-0.098\n";
  for (const auto& [dv, shown] :
       std::vector<std::pair<std::string, std::string>>{{"1e100", "1e+100"}, {"1e8", "1e+08"}, {"-200", "-200"}}) {
    const auto path = write_text("spike.csv", rows + "0.02,0,0,0," + dv + ",0,-0.098\n0.03,0,0,0,0,0,-0.098\n");
    const std::string e = read_error(path);
    EXPECT_NE(e.find("spike.csv:4: column 'dv_x_mps': " + shown + " over 0.01 s is a specific force of"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("beyond any accelerometer's range"), std::string::npos) << e;
  }
  const auto gyro = write_text("gyro.csv", rows + "0.02,5,0,0,0,0,-0.098\n");
  EXPECT_NE(read_error(gyro).find("column 'dtheta_x_rad': 5 over 0.01 s is an angular rate of 500 rad/s"),
            std::string::npos)
      << read_error(gyro);
  const auto rate = write_text("rate.csv",
                               "t_s,wx_radps,wy_radps,wz_radps,fx_mps2,fy_mps2,fz_mps2\n0.01,0,0,0,0,0,-9.8\n"
                               "0.02,0,0,0,0,0,-2e4\n");
  EXPECT_NE(read_error(rate).find("column 'fz_mps2': -20000 is beyond any accelerometer's range"), std::string::npos)
      << read_error(rate);
  // 100 g for 10 ms and 1000 deg/s are within what sensors measure.
  const auto ok = write_text("ok.csv", rows + "0.02,0.17,0,0,9.8,0,-0.098\n");
  EXPECT_EQ(read_error(ok), "");
}

TEST(ImuFile, NotARegularFileIsAnError) {
  EXPECT_NE(read_error("/dev/zero").find("IMU file '/dev/zero' is a device"), std::string::npos)
      << read_error("/dev/zero");
}

}  // namespace
}  // namespace deepnav
