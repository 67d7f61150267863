// A text product through its buffer: complete or absent, and a write that fails (a full
// disk, surfacing when the buffer is handed over) names the file and leaves nothing.
#include "signals/text_output_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ins/simulated_disk.hpp"

namespace deepnav {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  auto dir = fs::temp_directory_path() / ("deepnav_text_output_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

bool empty_folder(const fs::path& dir) { return fs::directory_iterator(dir) == fs::directory_iterator(); }

TEST(TextOutputFile, AppearsOnlyAfterCommit) {
  const auto dir = temp_dir("commit");
  const auto path = (dir / "a.csv").string();
  {
    TextOutputFile f(path);
    f.write("x,y\n1,2\n");
    EXPECT_FALSE(fs::exists(path));
    f.commit();
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "x,y\n1,2\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(TextOutputFile, AbandonedFileLeavesNothing) {
  const auto dir = temp_dir("abandon");
  {
    TextOutputFile f((dir / "b.csv").string());
    f.write("incomplete");
  }
  EXPECT_TRUE(empty_folder(dir));
  fs::remove_all(dir);
}

TEST(TextOutputFile, AFullDiskIsNamedAndLeavesNothing) {
  const auto dir = temp_dir("full");
  const auto path = (dir / "tracking.csv").string();
  simulated_disk::simulate(100 * 1024);
  TextOutputFile f(path);
  std::string error;
  try {
    for (int line = 0; line < 100000; ++line) f.write("1023,5,2,0.001,1.0,2.0,3.0,4.0,5.0,6.0,1234.5,1023000.0,45.0\n");
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  simulated_disk::simulate(std::nullopt);
  EXPECT_EQ(error, "cannot write '" + path + "': No space left on device");
  EXPECT_TRUE(empty_folder(dir));
  fs::remove_all(dir);
}

TEST(TextOutputFile, FailDropsTheTextAndAnEarlierRunsFile) {
  const auto dir = temp_dir("fail");
  const auto path = (dir / "pvt.csv").string();
  std::ofstream(path) << "an earlier run's fixes\n";
  TextOutputFile f(path);
  f.write("this run's first fixes\n");
  f.fail();
  EXPECT_TRUE(empty_folder(dir));
  fs::remove_all(dir);
}

TEST(TextOutputFile, UnwritablePathIsNamedInTheError) {
  try {
    TextOutputFile f("/nonexistent-folder/deeper/c.csv");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create '/nonexistent-folder/deeper/c.csv."), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace deepnav
