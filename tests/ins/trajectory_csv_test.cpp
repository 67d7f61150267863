#include "ins/sim/trajectory_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "ins/sim/trajectory_presets.hpp"

namespace deepnav {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::temp_directory_path() / ("deepnav_traj_" + name + ".csv")).string();
  std::ofstream(path) << text;
  return path;
}

/// Samples a preset at 10 Hz into a CSV file (geodetic form, with or without attitude).
std::string sample_preset(const Trajectory& traj, const std::string& name, bool with_attitude) {
  std::string text = with_attitude ? "t_s,lat_deg,lon_deg,height_m,roll_deg,pitch_deg,yaw_deg\n" : "t_s,lat_deg,lon_deg,height_m\n";
  for (int k = 0; k <= 600; ++k) {
    const double t = k * 0.1;
    const TrajectoryState s = traj.at(t);
    const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
    text += fmt::format("{:.1f},{:.12f},{:.12f},{:.6f}", t, llh.lat_rad * 180 / kPi, llh.lon_rad * 180 / kPi, llh.height_m);
    if (with_attitude) {
      const Eigen::Matrix3d C = s.q_b_n.toRotationMatrix();
      const double roll = std::atan2(C(2, 1), C(2, 2)), pitch = -std::asin(C(2, 0)), yaw = std::atan2(C(1, 0), C(0, 0));
      text += fmt::format(",{:.9f},{:.9f},{:.9f}", roll * 180 / kPi, pitch * 180 / kPi, yaw * 180 / kPi);
    }
    text += "\n";
  }
  return write_file(name, text);
}

TEST(TrajectoryCsv, ReproducesASampledCircle) {
  const wgs84::Llh start{37.5 * kPi / 180, 127.0 * kPi / 180, 50.0};
  const auto circle = make_preset_trajectory("land-circle", start, 0.0, 60.0);
  const auto csv = load_csv_trajectory(sample_preset(*circle, "circle", true));
  EXPECT_NEAR(csv->duration_s(), 60.0, 1e-9);
  for (double t = 1.0; t < 59.0; t += 0.737) {
    const TrajectoryState a = circle->at(t), b = csv->at(t);
    EXPECT_LT((a.r_ecef_m - b.r_ecef_m).norm(), 3e-3) << t;       // a few mm
    EXPECT_LT((a.v_ecef_mps - b.v_ecef_mps).norm(), 1e-3) << t;
    EXPECT_LT((a.a_ecef_mps2 - b.a_ecef_mps2).norm(), 2e-3) << t;
    EXPECT_LT(a.q_b_n.angularDistance(b.q_b_n), 1e-6) << t;
    EXPECT_LT((a.w_nb_b_radps - b.w_nb_b_radps).norm(), 1e-5) << t;
  }
  // Without attitude columns the heading follows the velocity: the same for a land vehicle.
  const auto csv_no_att = load_csv_trajectory(sample_preset(*circle, "circle_noatt", false));
  EXPECT_LT(circle->at(30.0).q_b_n.angularDistance(csv_no_att->at(30.0).q_b_n), 1e-4);
}

TEST(TrajectoryCsv, DerivativesAreConsistent) {
  const wgs84::Llh start{10.0 * kPi / 180, -60.0 * kPi / 180, 3000.0};
  const auto air = make_preset_trajectory("air-s", start, 1.0, 60.0);
  const auto csv = load_csv_trajectory(sample_preset(*air, "air_s", true));
  for (double t : {5.3, 22.2, 47.0}) {
    const double h = 1e-2;
    const Eigen::Vector3d v_fd = (csv->at(t + h).r_ecef_m - csv->at(t - h).r_ecef_m) / (2 * h);
    const TrajectoryState s = csv->at(t);
    EXPECT_LE((v_fd - s.v_ecef_mps).norm(), 1e-6 * s.v_ecef_mps.norm()) << t;
  }
}

TEST(TrajectoryCsv, BadInputNamesTheLine) {
  auto expect_error = [](const std::string& name, const std::string& text, const std::string& fragment) {
    const auto path = write_file(name, text);
    try {
      load_csv_trajectory(path);
      ADD_FAILURE() << name << ": no error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << name << ": " << e.what();
    }
  };
  const std::string h = "t_s,lat_deg,lon_deg,height_m\n";
  expect_error("header", "time,lat,lon,h\n0,1,2,3\n", ":1: expected the header");
  expect_error("number", h + "0,1,2,3\n1,1,x,3\n2,1,2,3\n3,1,2,3\n", ":3: column 'lon_deg': 'x' is not a number");
  expect_error("columns", h + "0,1,2,3\n1,1,2\n", ":3: expected 4 columns, got 3");
  expect_error("nan", h + "0,1,2,3\n1,nan,2,3\n", ":3: column 'lat_deg': value is not finite");
  expect_error("time", h + "0,1,2,3\n1,1,2,3\n1,1,2,3\n", ":4: time must increase strictly");
  expect_error("rows", h + "0,1,2,3\n1,1,2,3\n", "need at least 4 rows");
  expect_error("empty", "", "empty file");
  EXPECT_THROW(load_csv_trajectory("/nonexistent/trajectory.csv"), std::runtime_error);
  const auto ok = load_csv_trajectory(write_file("ok", h + "0,1,2,3\n1,1,2,3\n2,1,2,3\n3,1,2,3\n"));
  EXPECT_THROW(ok->at(3.5), std::out_of_range);
}

}  // namespace
}  // namespace deepnav
