// The output-file layer: a file takes its final name only when complete, its partial file
// is its process's own, a failed write removes both the partial file and an earlier run's
// file of the same name, a reservation survives a disk the others fill, and special files
// are written in place.
#include "ins/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ins/simulated_disk.hpp"

namespace deepnav {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The error a call throws ("" when none).
template <class Call>
std::string error_of(Call&& call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

class OutputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs the tests as parallel processes.
    dir_ = fs::path(DEEPNAV_BINARY_DIR) /
           ("output_file_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    simulated_disk::simulate(std::nullopt);
    fs::remove_all(dir_);
  }
  /// The folder's file names, sorted.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

TEST_F(OutputFileTest, AppearsOnlyWhenCommittedUnderAPartialNameOfItsProcess) {
  const fs::path path = dir_ / "pvt.csv";
  OutputFile f(path);
  f.write("t_s,x\n");
  f.write("1,2\n");
  EXPECT_EQ(f.partial_path(), dir_ / ("pvt.csv." + std::to_string(::getpid()) + ".partial"));
  EXPECT_EQ(listing(), std::vector<std::string>{f.partial_path().filename().string()});
  f.commit();
  EXPECT_EQ(listing(), std::vector<std::string>{"pvt.csv"});
  EXPECT_EQ(read_all(path), "t_s,x\n1,2\n");
  EXPECT_EQ(f.bytes_written(), 10u);
}

TEST_F(OutputFileTest, TwoWritersOfOneFileNeverShareAPartialFile) {
  const fs::path path = dir_ / "tracking.csv";
  OutputFile first(path), second(path);
  EXPECT_NE(first.partial_path(), second.partial_path());
  first.write("first\n");
  second.write("second\n");
  first.commit();
  EXPECT_EQ(read_all(path), "first\n");
  second.commit();
  EXPECT_EQ(read_all(path), "second\n");  // whole files replace each other, never spliced
}

TEST_F(OutputFileTest, ALinkPlantedUnderThePartialNameIsNotFollowed) {
  const fs::path path = dir_ / "pvt.csv";
  const fs::path planted = dir_ / ("pvt.csv." + std::to_string(::getpid()) + ".partial");
  fs::create_symlink("/dev/full", planted);
  OutputFile f(path);
  EXPECT_NE(f.partial_path(), planted);
  f.write("ok\n");
  f.commit();
  EXPECT_EQ(read_all(path), "ok\n");
  EXPECT_TRUE(fs::is_symlink(planted));
}

TEST_F(OutputFileTest, DestroyedBeforeCommitLeavesAnEarlierRunsFileAsItWas) {
  const fs::path path = dir_ / "nav.rnx";
  std::ofstream(path) << "earlier run\n";
  {
    OutputFile f(path);
    f.write("incomplete");
  }
  EXPECT_EQ(listing(), std::vector<std::string>{"nav.rnx"});
  EXPECT_EQ(read_all(path), "earlier run\n");
}

TEST_F(OutputFileTest, AFullDiskRemovesThePartialFileAndAnEarlierRunsFile) {
  const fs::path path = dir_ / "tracking.csv";
  std::ofstream(path) << "earlier run\n";
  simulated_disk::simulate(100);
  OutputFile f(path);
  f.write(std::string(60, 'x'));
  const std::string error = error_of([&] { f.write(std::string(60, 'y')); });
  EXPECT_EQ(error, "cannot write '" + path.string() +
                       "': No space left on device (an earlier run's file of that name is removed)");
  EXPECT_TRUE(f.failed());
  EXPECT_TRUE(listing().empty());
  // Its space is free again for the other files.
  OutputFile other(dir_ / "pvt.csv");
  other.write(std::string(100, 'z'));
  other.commit();
  EXPECT_EQ(fs::file_size(dir_ / "pvt.csv"), 100u);
  // A failed file takes nothing more.
  EXPECT_THROW(f.write("more"), std::logic_error);
  EXPECT_THROW(f.commit(), std::logic_error);
}

TEST_F(OutputFileTest, AReservationHoldsItsSpaceAndIsCutToTheContent) {
  simulated_disk::simulate(1000);
  OutputFile summary(dir_ / "summary.json");
  summary.reserve(400);
  OutputFile tracking(dir_ / "tracking.csv");
  tracking.write(std::string(600, 't'));
  EXPECT_NE(error_of([&] { tracking.write("t"); }), "");  // the disk is full
  const std::string text = "{\"products_failed\": [\"tracking.csv\"]}\n";
  summary.write(text);
  summary.commit();
  EXPECT_EQ(read_all(dir_ / "summary.json"), text);
  EXPECT_EQ(listing(), std::vector<std::string>{"summary.json"});
  // What the reservation did not use is free again; the rest of the disk too (tracking.csv failed).
  OutputFile after(dir_ / "after.txt");
  after.write(std::string(1000 - text.size(), 'a'));
  EXPECT_NE(error_of([&] { after.write("a"); }), "");
}

TEST_F(OutputFileTest, AReservationTheDiskCannotHoldIsRefusedAndTheFileGoesOn) {
  simulated_disk::simulate(100);
  OutputFile f(dir_ / "summary.json");
  EXPECT_EQ(error_of([&] { f.reserve(1000); }),
            "cannot reserve 1000 bytes for '" + (dir_ / "summary.json").string() + "': No space left on device");
  f.write("{}\n");
  f.commit();
  EXPECT_EQ(read_all(dir_ / "summary.json"), "{}\n");
}

TEST_F(OutputFileTest, ADeviceIsWrittenInPlaceAndItsErrorNamed) {
  OutputFile full("/dev/full");
  EXPECT_EQ(full.partial_path(), fs::path("/dev/full"));
  EXPECT_EQ(error_of([&] { full.write("{}\n"); }), "cannot write '/dev/full': No space left on device");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));  // still the device
  OutputFile null("/dev/null");
  null.write("discarded");
  null.commit();
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST_F(OutputFileTest, ALinkIsFollowedAndItsTargetReplaced) {
  const fs::path target = dir_ / "target.json", link = dir_ / "link.json";
  std::ofstream(target) << "old\n";
  fs::create_symlink(target, link);
  OutputFile f(link);
  f.write("new\n");
  f.commit();
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_all(target), "new\n");
}

TEST_F(OutputFileTest, AFolderOrAMissingFolderIsNamedInTheError) {
  EXPECT_EQ(error_of([&] { OutputFile f(dir_); }), "cannot write '" + dir_.string() + "': it is a folder");
  const std::string error = error_of([&] { OutputFile f(dir_ / "missing" / "a.csv"); });
  EXPECT_EQ(error.rfind("cannot create '" + (dir_ / "missing" / "a.csv").string() + ".", 0), 0u) << error;
  EXPECT_NE(error.find(".partial': No such file or directory"), std::string::npos) << error;
}

TEST(PartialFileNames, AreRecognisedForTheirProductOnly) {
  EXPECT_TRUE(is_partial_file_of("pvt.csv.1234.partial", "pvt.csv"));
  EXPECT_TRUE(is_partial_file_of("pvt.csv.1234-2.partial", "pvt.csv"));
  EXPECT_TRUE(is_partial_file_of("pvt.csv.partial", "pvt.csv"));
  EXPECT_FALSE(is_partial_file_of("pvt.csv", "pvt.csv"));
  EXPECT_FALSE(is_partial_file_of("pvt.csv.partial", "tracking.csv"));
  EXPECT_FALSE(is_partial_file_of("pvt.csv.old.partial", "pvt.csv"));
  EXPECT_FALSE(is_partial_file_of("pvt.csv.12-.partial", "pvt.csv"));
  EXPECT_FALSE(is_partial_file_of("pvt.csvx.12.partial", "pvt.csv"));
}

}  // namespace
}  // namespace deepnav
