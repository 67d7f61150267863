#include "tools/bench/coupling_sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>
#include <optional>

#include "ins/input_error.hpp"
#include "signals/sim/error_presets.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/child_process.hpp"
#include "tools/bench/coupling_report.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;

void check_settings(const CouplingSweepSettings& o) {
  if (o.runs < 1) throw InputError("--runs must be at least 1");
  if (o.first_run < 0) throw InputError("--first-run must be 0 or more");
  for (const auto& m : o.point.modes) {
    if (m != "loose" && m != "tight" && m != "ultra" && m != "scalar")
      throw InputError("--modes: unknown mode '" + m + "' (expected scalar, loose, tight, ultra)");
  }
  try {
    (void)error_preset(o.point.errors);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--errors: ") + e.what());
  }
  for (const auto& t : o.trajectories) (void)coupling_seed_index(t);
  if (o.score_at_s >= o.point.duration_s) throw InputError("--score-at must fall inside --duration");
}

/// Runs the points `jobs` at a time, each written to `out_dir` when done.
void run_points(const std::vector<CouplingPoint>& todo, const CouplingSweepSettings& o,
                const std::function<void(double)>& progress) {
  std::mutex done_mutex;
  std::size_t done = 0;
  const unsigned jobs = std::max(1u, o.jobs);
  for (std::size_t first = 0; first < todo.size(); first += jobs) {
    std::vector<std::future<void>> batch;
    for (std::size_t k = first; k < std::min(todo.size(), first + jobs); ++k) {
      batch.push_back(std::async(std::launch::async, [&, k] {
        write_coupling_point(o.out_dir, todo[k], run_coupling_point(todo[k], o.work_dir));
        const std::lock_guard<std::mutex> lock(done_mutex);
        ++done;
        if (progress) progress(static_cast<double>(done) / static_cast<double>(todo.size()));
      }));
    }
    for (auto& f : batch) f.get();
  }
}

void plot(const CouplingSweepSettings& o) {
  if (o.csv_path.empty()) throw InputError("--plot needs --csv (the plot is drawn from it)");
  const std::string cmd = fmt::format("/usr/bin/python3 {}/tools/plots/plot_coupling.py '{}' '{}'", DEEPNAV_SOURCE_DIR,
                                      o.csv_path, o.plot_path);
  if (std::system(cmd.c_str()) != 0) throw InputError("plotting failed: " + cmd);
}

}  // namespace

std::vector<CouplingPoint> coupling_sweep_points(const CouplingSweepSettings& o) {
  std::vector<CouplingPoint> points;
  for (const auto& t : o.trajectories)
    for (int r = o.first_run; r < o.first_run + o.runs; ++r) points.push_back({t, r, o.point});
  return points;
}

void run_coupling_sweep(CouplingSweepSettings o, const std::function<void(double)>& progress) {
  check_settings(o);
  const bool own_work_dir = o.work_dir.empty();
  o.work_dir = bench_scratch_dir(o.work_dir, "bench_coupling");
  // Without --out the points live in a folder of their own that is removed afterwards.
  const bool keep_points = !o.out_dir.empty();
  if (!keep_points) o.out_dir = (fs::path(o.work_dir) / fmt::format("points_{}", getpid())).string();
  o.out_dir = fs::absolute(o.out_dir).string();

  const std::vector<CouplingPoint> points = coupling_sweep_points(o);
  std::vector<CouplingPoint> todo;
  for (const auto& p : points)
    if (load_coupling_point(o.out_dir, p).is_null()) todo.push_back(p);
  if (o.list_commands) {
    for (const auto& p : todo)
      fmt::print("{}\n", shell_command_line(coupling_point_command(self_executable(), p, o.out_dir)));
    return;
  }
  if (keep_points) {
    spdlog::info("{} points, {} already finished in {}, {} to run", points.size(), points.size() - todo.size(),
                 o.out_dir, todo.size());
  }
  run_points(todo, o, progress);

  std::vector<nlohmann::json> finished;
  for (const auto& p : points) finished.push_back(load_coupling_point(o.out_dir, p));
  if (!keep_points) fs::remove_all(o.out_dir);
  std::error_code ignored;  // a folder of our own, empty by now (each point removes its IF)
  if (own_work_dir) fs::remove(o.work_dir, ignored);

  coupling_report(o, finished, keep_points ? std::optional<std::string>(o.out_dir) : std::nullopt).emit(o.json_path);
  if (!o.csv_path.empty()) write_coupling_csv(o.csv_path, finished);
  if (!o.plot_path.empty()) plot(o);
}

}  // namespace deepnav::bench
