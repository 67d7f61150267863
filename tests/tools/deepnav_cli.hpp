#pragma once
// Runs the `deepnav` binary of this build (DEEPNAV_CLI) from a test: how the tools tests
// read a recorded command back with the command line's own option definitions.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tools/bench/child_process.hpp"

namespace deepnav::bench::test {

struct CliResult {
  int exit_code = 0;
  std::string output;  ///< stdout and stderr together
};

/// `deepnav args...`; `args` start after the program name.
inline CliResult run_deepnav(const std::vector<std::string>& args) {
  static int calls = 0;
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() /
      ("deepnav_tools_test_" + std::to_string(getpid()) + "_" + std::to_string(++calls) + ".log");
  std::vector<std::string> argv{DEEPNAV_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  CliResult r;
  r.exit_code = wait_child(start_child(argv, log.string()));
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  r.output = text.str();
  std::filesystem::remove(log);
  return r;
}

/// A folder of the test's own, removed with it.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// True when `words` appear in `argv` one right after the other.
inline bool contains_words(const std::vector<std::string>& argv, const std::vector<std::string>& words) {
  return std::search(argv.begin(), argv.end(), words.begin(), words.end()) != argv.end();
}

inline bool has_flag(const std::vector<std::string>& argv, const std::string& flag) {
  for (const auto& a : argv)
    if (a == flag) return true;
  return false;
}

}  // namespace deepnav::bench::test
