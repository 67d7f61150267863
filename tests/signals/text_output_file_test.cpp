#include "signals/text_output_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace deepnav {
namespace {

std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("deepnav_text_output_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(TextOutputFile, AppearsOnlyAfterCommit) {
  const auto dir = temp_dir("commit");
  const auto path = (dir / "a.csv").string();
  {
    TextOutputFile f(path);
    f.write("x,y\n1,2\n");
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_TRUE(std::filesystem::exists(path + ".partial"));
    f.commit();
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "x,y\n1,2\n");
}

TEST(TextOutputFile, AbandonedFileLeavesNothing) {
  const auto dir = temp_dir("abandon");
  const auto path = (dir / "b.csv").string();
  {
    TextOutputFile f(path);
    f.write("incomplete");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(TextOutputFile, UnwritablePathIsNamedInTheError) {
  try {
    TextOutputFile f("/nonexistent-folder/deeper/c.csv");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/deeper/c.csv.partial"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace deepnav
