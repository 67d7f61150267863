#include "receiver/observations/solution_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "ins/frames.hpp"

namespace deepnav {
namespace {

std::string write_text(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::path(DEEPNAV_BINARY_DIR) / ("solution_file_test_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path) {
  try {
    read_rtklib_pos(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

constexpr char kHeader[] =
    "% program   : RTKLIB ver.2.4.3\n"
    "%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns\n";

TEST(SolutionFile, ReadsCalendarAndWeekTimes) {
  const std::string path = write_text(
      "good.pos", std::string(kHeader) +
                      "2025/08/28 17:30:39.750   40.096704347 -105.147073712  1592.8589   5   6   7.2660   4.7145\n"
                      "2381 408640.000   40.096704290 -105.147074038  1592.9655   1  12\n\n");
  const std::vector<SolutionPoint> p = read_rtklib_pos(path);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].t.week, 2381);
  EXPECT_NEAR(p[0].t.sow, 4 * 86400.0 + 17 * 3600.0 + 30 * 60.0 + 39.75, 1e-6);
  EXPECT_NEAR(p[0].llh.lat_rad * 180.0 / M_PI, 40.096704347, 1e-12);
  EXPECT_NEAR(p[0].llh.height_m, 1592.8589, 1e-9);
  EXPECT_EQ(p[0].quality, 5);
  EXPECT_EQ(p[0].satellites, 6);
  EXPECT_NEAR(p[1].t.seconds_since(p[0].t), 0.25, 1e-6);
  EXPECT_EQ(p[1].quality, 1);
}

TEST(SolutionFile, BadFilesGiveErrorsNamingFileLineAndField) {
  const std::string good = "2025/08/28 17:30:39.750   40.096704347 -105.147073712  1592.8589   5   6\n";
  const std::string fields = write_text("fields.pos", good + "2025/08/28 17:30:40.000   40.0967 -105.1470\n");
  EXPECT_EQ(error_of(fields), fields + ":2: expected time, latitude, longitude, height, Q; found 4 fields");
  const std::string date =
      write_text("date.pos", std::string(kHeader) + "2025/13/28 17:30:39.750 40.1 -105.1 1592.9 5 6\n");
  EXPECT_EQ(error_of(date), date + ":3: date '2025/13/28' is not yyyy/mm/dd");
  const std::string week = write_text("week.pos", "2381x 408640.0 40.1 -105.1 1592.9 5 6\n");
  EXPECT_EQ(error_of(week), week + ":1: GPS week: '2381x' is not a number");
  const std::string time = write_text("time.pos", "2025/08/28 25:30:39.750 40.1 -105.1 1592.9 5 6\n");
  EXPECT_EQ(error_of(time), time + ":1: time '25:30:39.750' is not hh:mm:ss.sss");
  const std::string number = write_text("number.pos", good + "2025/08/28 17:30:40.000 40.1 -105.1 abc 5 6\n");
  EXPECT_NE(error_of(number).find(number + ":2: height: 'abc' is not a number"), std::string::npos);
  const std::string ecef = write_text("ecef.pos", "2025/08/28 17:30:40.000 -1276963.1 -4717222.7 4087221.9 5 6\n");
  EXPECT_NE(error_of(ecef).find(ecef + ":1: latitude/longitude"), std::string::npos);
  EXPECT_NE(error_of(ecef).find("is the file in ECEF?"), std::string::npos);
  const std::string empty = write_text("empty.pos", kHeader);
  EXPECT_EQ(error_of(empty), "solution file '" + empty + "' holds no solutions");
  EXPECT_EQ(error_of("/nonexistent/ref.pos"), "cannot open solution file '/nonexistent/ref.pos'");
}

TEST(SolutionFile, ErrorsAboutTheMeanOffset) {
  // A reference track and a solution offset from it by (3, -2, 5) m east/north/up plus
  // +-0.5 m east alternating: the mean offset comes out, the scatter is the alternation.
  std::vector<SolutionPoint> ref, sol;
  const wgs84::Llh origin{40.0 * M_PI / 180.0, -105.0 * M_PI / 180.0, 1600.0};
  for (int k = 0; k < 40; ++k) {
    SolutionPoint r;
    r.t = GpsTime{2381, 408640.0 + 0.25 * k};
    const Eigen::Vector3d track_ned(0.5 * k, 0.2 * k, 0.0);
    r.llh = wgs84::ecef_to_llh(wgs84::llh_to_ecef(origin) + ned_to_ecef_vector(origin, track_ned));
    ref.push_back(r);
    SolutionPoint s = r;
    s.t = r.t.plus_seconds(0.001);  // within the 10 ms match
    const double east = 3.0 + (k % 2 == 0 ? 0.5 : -0.5);
    s.llh =
        wgs84::ecef_to_llh(wgs84::llh_to_ecef(r.llh) + ned_to_ecef_vector(origin, Eigen::Vector3d(-2.0, east, -5.0)));
    sol.push_back(s);
  }
  SolutionPoint far = sol.back();
  far.t = far.t.plus_seconds(0.5);  // no reference epoch within 10 ms: not compared
  sol.push_back(far);
  const ReferenceErrors e = reference_errors(sol, ref);
  EXPECT_EQ(e.epochs, 40);
  EXPECT_NEAR(e.mean_offset_enu_m.x(), 3.0, 1e-3);
  EXPECT_NEAR(e.mean_offset_enu_m.y(), -2.0, 1e-3);
  EXPECT_NEAR(e.mean_offset_enu_m.z(), 5.0, 1e-3);
  EXPECT_NEAR(e.scatter_rms_horizontal_m, 0.5, 1e-3);
  EXPECT_NEAR(e.scatter_max_horizontal_m, 0.5, 1e-3);
  EXPECT_NEAR(e.scatter_max_3d_m, 0.5, 1e-3);
  EXPECT_NEAR(e.rms_horizontal_m, std::sqrt((3.5 * 3.5 + 2.5 * 2.5) / 2.0 + 4.0), 1e-3);
  EXPECT_DOUBLE_EQ(e.json()["about_mean_offset"]["rms_horizontal_m"].get<double>(), 0.5);
}

TEST(SolutionFile, NoEpochScoredGivesNoStatistics) {
  // Not a perfect score of zeros: nothing was compared, so nothing is stated.
  SolutionPoint r;
  r.t = GpsTime{2381, 408600.0};
  r.llh = {0.7, -1.8, 1600.0};
  SolutionPoint s = r;
  s.t = r.t.plus_seconds(1.0);
  const ReferenceErrors e = reference_errors({s}, {r});
  EXPECT_EQ(e.epochs, 0);
  const nlohmann::json j = e.json();
  EXPECT_EQ(j["epochs"], 0);
  EXPECT_TRUE(j["mean_offset_enu_m"].is_null());
  EXPECT_TRUE(j["rms_horizontal_m"].is_null());
  EXPECT_TRUE(j["rms_3d_m"].is_null());
  for (const auto& [key, value] : j["about_mean_offset"].items()) EXPECT_TRUE(value.is_null()) << key;
  EXPECT_TRUE(reference_errors({}, {}).json()["about_mean_offset"]["max_3d_m"].is_null());
}

}  // namespace
}  // namespace deepnav
