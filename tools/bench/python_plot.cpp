#include "tools/bench/python_plot.hpp"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <filesystem>

#include "ins/input_error.hpp"

namespace deepnav::bench {
namespace {

constexpr const char* kPython = "/usr/bin/python3";

/// Single-quoted for the shell; a quote inside becomes '\''.
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool run_plot_script(const std::string& script, const std::string& plots_dir) {
  const std::filesystem::path path = std::filesystem::path(DEEPNAV_SOURCE_DIR) / "tools" / "plots" / script;
  if (!std::filesystem::exists(kPython)) {
    spdlog::warn("no {}: PNG plots skipped (data left in {})", kPython, plots_dir);
    return false;
  }
  if (std::system((std::string(kPython) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) != 0) {
    spdlog::warn("python3-matplotlib is not installed: PNG plots skipped (data left in {})", plots_dir);
    return false;
  }
  if (!std::filesystem::exists(path)) {
    spdlog::warn("plot script {} not found: PNG plots skipped", path.string());
    return false;
  }
  const std::string command = std::string(kPython) + " " + shell_quote(path.string()) + " " + shell_quote(plots_dir);
  if (std::system(command.c_str()) != 0) {
    spdlog::warn("plot script {} failed: some PNG plots may be missing in {}", script, plots_dir);
    return false;
  }
  return true;
}

void make_plots_dir(const std::string& plots_dir) {
  std::error_code ec;
  std::filesystem::create_directories(plots_dir, ec);
  if (ec) throw InputError("cannot create plots directory '" + plots_dir + "': " + ec.message());
}

}  // namespace deepnav::bench
