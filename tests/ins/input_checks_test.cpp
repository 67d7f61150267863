// The checks every reader makes before it opens an input, and the YAML duplicate-key check.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>

#include "ins/input_file.hpp"
#include "ins/yaml_checks.hpp"
#include "tests/support/error_message.hpp"

namespace deepnav {
namespace {

using testing::error_of;

TEST(InputFile, RegularFilesOnlyAndWithinTheSizeLimit) {
  const auto dir = std::filesystem::path(DEEPNAV_BINARY_DIR) / "input_checks_test";
  std::filesystem::create_directories(dir);
  const auto file = (dir / "small.txt").string();
  std::ofstream(file) << "twelve bytes";
  EXPECT_EQ(error_of([&] { check_input_file(file, "test file"); }), "");
  EXPECT_EQ(error_of([&] { check_input_file(file, "test file", 12); }), "");
  EXPECT_NE(error_of([&] { check_input_file(file, "test file", 11); }).find("is 12 bytes, more than the 11"),
            std::string::npos);
  EXPECT_NE(error_of([&] { check_input_file(dir.string(), "test file"); }).find("is a directory"), std::string::npos);
  EXPECT_NE(
      error_of([] { check_input_file("/dev/zero", "scenario file"); }).find("scenario file '/dev/zero' is a device"),
      std::string::npos);
  EXPECT_NE(error_of([&] { check_input_file((dir / "missing").string(), "test file"); }).find("No such file"),
            std::string::npos);
  // A FIFO without a writer: an error at once, where opening it would block forever.
  const auto fifo = (dir / "fifo").string();
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(error_of([&] { check_input_file(fifo, "sample file"); }).find("is a FIFO"), std::string::npos);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  std::filesystem::remove(fifo);
}

TEST(YamlChecks, DuplicateKeysAnywhereAreErrors) {
  EXPECT_EQ(error_of([] { check_unique_keys(YAML::Load("a: 1\nb: {c: 2, d: 3}\ne: [{f: 1}, {f: 2}]\n"), "x.yaml"); }),
            "");
  EXPECT_EQ(error_of([] { check_unique_keys(YAML::Load("a: 1\nb: 2\na: 3\n"), "x.yaml"); }),
            "x.yaml:3: key 'a' appears twice in one mapping (lines 1 and 3)");
  EXPECT_EQ(error_of([] { check_unique_keys(YAML::Load("top:\n  k: 1\n  k: 2\n"), "x.yaml"); }),
            "x.yaml:3: key 'k' appears twice in one mapping (lines 2 and 3)");
  EXPECT_EQ(error_of([] { check_unique_keys(YAML::Load("l:\n  - {x: 1, x: 2}\n"), "x.yaml"); }),
            "x.yaml:2: key 'x' appears twice in one mapping (lines 2 and 2)");
}

}  // namespace
}  // namespace deepnav
