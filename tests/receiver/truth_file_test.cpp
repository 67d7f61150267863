// The truth file reader: column names must be unique (a repeated name once made the reader
// index past a row), and every value a whole finite number (std::stod used to take "nan",
// "inf" and the "123.4" of "123.4junk").
#include "receiver/products/truth_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace deepnav {
namespace {

const std::string kHeader = "t_s,x_ecef_m,y_ecef_m,z_ecef_m,vx_ecef_mps,vy_ecef_mps,vz_ecef_mps";

std::string write_text(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::path(DEEPNAV_BINARY_DIR) / ("truth_file_test_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path) {
  try {
    TruthFile t(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(TruthFile, ReadsAndInterpolates) {
  const auto path = write_text("good.csv", kHeader + "\n0,1,2,3,4,5,6\n1,3,4,5,6,7,8\n");
  const TruthFile t(path);
  const auto s = t.at(0.5);
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->r_ecef_m.x(), 2.0);
  EXPECT_DOUBLE_EQ(s->v_ecef_mps.z(), 7.0);
  EXPECT_FALSE(t.at(1.5));
}

TEST(TruthFile, DuplicateColumnNamesAreAnErrorNotAnOverflow) {
  // The reproducer: twenty columns named 'a' and rows of 8 values.
  const std::string path = std::string(DEEPNAV_SOURCE_DIR) + "/tests/data/repro/truth_dup_header_oob.csv";
  const std::string e = error_of(path);
  EXPECT_NE(e.find("truth_dup_header_oob.csv:1: column name 'a' appears twice (columns 1 and 2)"), std::string::npos)
      << e;
  const std::string twice = error_of(write_text("twice.csv", kHeader + ",t_s\n0,1,2,3,4,5,6,7\n1,1,2,3,4,5,6,7\n"));
  EXPECT_NE(twice.find(":1: column name 't_s' appears twice (columns 1 and 8)"), std::string::npos) << twice;
}

TEST(TruthFile, RowsNeedTheHeadersColumnCount) {
  const std::string e = error_of(write_text("short.csv", kHeader + "\n0,1,2,3,4,5,6\n1,1,2,3\n"));
  EXPECT_NE(e.find(":3: expected 7 columns (as the header), got 4"), std::string::npos) << e;
}

TEST(TruthFile, NonFiniteAndPartlyNumericValuesAreErrors) {
  for (const auto& [bad, column] : std::vector<std::pair<std::string, std::string>>{{"nan", "x_ecef_m"},
                                                                                    {"inf", "x_ecef_m"},
                                                                                    {"123.4junk", "x_ecef_m"},
                                                                                    {"", "x_ecef_m"},
                                                                                    {"1e999", "x_ecef_m"}}) {
    const std::string e = error_of(write_text("bad.csv", kHeader + "\n0,1,2,3,4,5,6\n1," + bad + ",2,3,4,5,6\n"));
    EXPECT_NE(e.find(":3: column '" + column + "': '" + bad + "' is not a finite number"), std::string::npos)
        << bad << ": " << e;
  }
  const std::string t = error_of(write_text("time.csv", kHeader + "\n0,1,2,3,4,5,6\nnan,1,2,3,4,5,6\n"));
  EXPECT_NE(t.find(":3: column 't_s': 'nan' is not a finite number"), std::string::npos) << t;
}

TEST(TruthFile, NotARegularFileIsAnError) {
  const std::string e = error_of("/dev/zero");
  EXPECT_NE(e.find("truth file '/dev/zero' is a device"), std::string::npos) << e;
}

}  // namespace
}  // namespace deepnav
