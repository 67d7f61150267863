#include "ins/sim/trajectory_csv.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

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
  std::string text =
      with_attitude ? "t_s,lat_deg,lon_deg,height_m,roll_deg,pitch_deg,yaw_deg\n" : "t_s,lat_deg,lon_deg,height_m\n";
  for (int k = 0; k <= 600; ++k) {
    const double t = k * 0.1;
    const TrajectoryState s = traj.at(t);
    const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
    text +=
        fmt::format("{:.1f},{:.12f},{:.12f},{:.6f}", t, llh.lat_rad * 180 / kPi, llh.lon_rad * 180 / kPi, llh.height_m);
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
    EXPECT_LT((a.r_ecef_m - b.r_ecef_m).norm(), 3e-3) << t;  // a few mm
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

// Found by fuzzing (tests/fuzz/trajectory_csv_fuzzer.cpp): the attitude rates' finite
// differences (steps of 2 ms) reached outside a file spanning under 8 ms, and at() threw
// std::out_of_range for times inside the file; in a file whose first time is just below a
// power of two, (t0 + 4 ms) - 4 ms rounds to an ulp before t0, with the same result.
TEST(TrajectoryCsv, EveryTimeInsideTheFileIsDefined) {
  const std::string rows[] = {"-3052000,4045000,3858000\n", "-3052000.001,4045000,3858000\n"};
  for (const auto& [name, times] : std::initializer_list<std::pair<const char*, std::array<double, 4>>>{
           {"span_3ms", {0.0, 0.001, 0.002, 0.003}}, {"rounding", {3.9972658455388332, 4.5, 5.0, 6.0}}}) {
    std::string text = "t_s,x_ecef_m,y_ecef_m,z_ecef_m\n";
    for (std::size_t i = 0; i < times.size(); ++i) text += fmt::format("{:.17g},", times[i]) + rows[i % 2];
    std::istringstream in(text);
    const auto trajectory = load_csv_trajectory(in, name);
    for (double t : {times.front(), (times.front() + times.back()) / 2, times.back()})
      EXPECT_NO_THROW(trajectory->at(t)) << name << " at " << t;
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

TEST(TrajectoryCsv, JumpsAndPositionsNoReceiverCanHaveAreErrors) {
  // The reproducer: latitude 37.5 to -37.5 deg between two rows 10 ms apart (the
  // synthesizer once spun forever on the range rate that made).
  const std::string repro = std::string(DEEPNAV_SOURCE_DIR) + "/tests/data/repro/traj_teleport.csv";
  try {
    load_csv_trajectory(repro);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("traj_teleport.csv:7: the position moves"), std::string::npos) << m;
    EXPECT_NE(m.find("faster than 12000 m/s"), std::string::npos) << m;
  }
  const std::string h = "t_s,lat_deg,lon_deg,height_m\n";
  const std::string e = "t_s,x_ecef_m,y_ecef_m,z_ecef_m\n";
  for (const auto& [text, fragment] : std::vector<std::pair<std::string, std::string>>{
           {h + "0,1,2,3\n1,1,2,3\n2,1,2,1e9\n3,1,2,3\n", ":4: height_m 1e+09 is outside [-12000, 1e+08] m"},
           {h + "0,1,2,3\n1,1,2,3\n2,1,2,-20000\n3,1,2,3\n", ":4: height_m -20000 is outside"},
           {e + "0,0,0,0\n1,0,0,0\n2,0,0,0\n3,0,0,0\n", ":2: position is 0 m from the Earth's centre"},
           {h + "0,1,2,3\n1,1,2.2,3\n2,1,2,3\n3,1,2,3\n", ":3: the position moves"}}) {
    try {
      load_csv_trajectory(write_file("bad_motion", text));
      ADD_FAILURE() << fragment << ": no error";
    } catch (const std::runtime_error& err) {
      EXPECT_NE(std::string(err.what()).find(fragment), std::string::npos) << err.what();
    }
  }
  // An airliner (250 m/s) and a LEO satellite (7.7 km/s) are fine.
  EXPECT_NO_THROW(load_csv_trajectory(write_file("fast", h + "0,0,0,10000\n1,0,0.00225,10000\n2,0,0.0045,10000\n"
                                                             "3,0,0.00675,10000\n")));
  EXPECT_NO_THROW(load_csv_trajectory(write_file("leo", h + "0,0,0,400000\n1,0,0.06,400000\n2,0,0.12,400000\n"
                                                            "3,0,0.18,400000\n")));
}

}  // namespace
}  // namespace deepnav
