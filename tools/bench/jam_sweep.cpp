#include "tools/bench/jam_sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "ins/input_error.hpp"
#include "receiver/mitigation/mitigation_config.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/child_process.hpp"
#include "tools/bench/jam_report.hpp"
#include "tools/bench/python_plot.hpp"
#include "tools/bench/receiver_modes.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ','))
    if (!item.empty()) out.push_back(item);
  if (out.empty()) throw InputError(option + ": expected a comma-separated list, got '" + text + "'");
  return out;
}

/// Runs the commands with at most `jobs` at a time; returns how many failed.
int run_parallel(const std::vector<std::pair<JamPoint, std::vector<std::string>>>& work, const std::string& out_dir,
                 int jobs) {
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0, done = 0;
  int failed = 0;
  const fs::path logs = fs::path(out_dir) / "logs";
  fs::create_directories(logs);
  while (done < work.size()) {
    while (next < work.size() && static_cast<int>(running.size()) < jobs) {
      const std::string log = (logs / (point_id(work[next].first) + ".log")).string();
      fs::remove(log);
      running[start_child(work[next].second, log)] = next;
      ++next;
    }
    int status = 0;
    const pid_t pid = wait_any_child(status);
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const JamPoint& p = work[it->second].first;
    ++done;
    if (status != 0) ++failed;
    fmt::print(
        "[{}/{}] {} {}\n", done, work.size(), point_id(p),
        status == 0 ? "done" : fmt::format("FAILED (exit {}, see {}/{}.log)", status, logs.string(), point_id(p)));
    std::fflush(stdout);
    running.erase(it);
  }
  return failed;
}

}  // namespace

std::string default_jam_scenario() { return source_tree_path("data/scenarios/jam_static_32s.yaml"); }

std::vector<double> parse_js_range(const std::string& text) {
  std::vector<double> parts;
  std::stringstream s(text);
  std::string item;
  try {
    while (std::getline(s, item, ':')) {
      std::size_t used = 0;
      parts.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    }
  } catch (const std::exception&) {
    throw InputError("--js '" + text + "': expected FROM:TO:STEP in dB (e.g. 20:60:5) or one value");
  }
  if (parts.size() == 1) parts = {parts[0], parts[0], 1.0};
  if (parts.size() != 3 || !(parts[2] > 0.0) || !(parts[1] >= parts[0]) || parts[0] < -50.0 || parts[1] > 120.0)
    throw InputError("--js '" + text + "': expected FROM:TO:STEP with FROM <= TO within [-50, 120] dB and STEP > 0");
  std::vector<double> values;
  for (int k = 0;; ++k) {
    const double v = parts[0] + k * parts[2];
    if (v > parts[1] + 1e-9) break;
    values.push_back(std::round(v * 10.0) / 10.0);
  }
  return values;
}

std::vector<JamPoint> jam_sweep_points(const JamSweepSettings& o) {
  Scenario base;
  try {
    base = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
  require_scenario_systems(base, o.systems, o.scenario);
  const auto jammers = split_list(o.jammers, "--jammer");
  for (const auto& j : jammers) benchmark_jammer(j, 0.0, 0.0);  // rejects unknown types
  const auto modes = split_list(o.modes, "--modes");
  for (const auto& m : modes)
    if (find_receiver_mode(m).needs_imu && !base.imu.enabled)
      throw InputError(
          fmt::format("--modes {}: mode '{}' needs an IMU, but scenario '{}' has no imu: section "
                      "(e.g. imu: {{grade: tactical, rate_hz: 100}})",
                      o.modes, m, o.scenario));
  const auto mitigations = split_list(o.mitigations, "--mitigation");
  for (const auto& m : mitigations) {
    try {
      parse_mitigation_mode(m);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--mitigation: ") + e.what());
    }
  }
  if (o.runs < 1) throw InputError("--runs: expected at least 1");
  if (!(o.onset_s >= 0.0 && o.onset_s < base.duration_s))
    throw InputError(fmt::format("--onset {} s: expected within the scenario's {} s", o.onset_s, base.duration_s));
  std::vector<JamPoint> points;
  for (const auto& jammer : jammers)
    for (const auto& mode : modes)
      for (const auto& mitigation : mitigations)
        for (int r = 0; r < o.runs; ++r)
          for (double js : parse_js_range(o.js))
            points.push_back({o.scenario, jammer, js, mode, mitigation, base.seed + static_cast<std::uint64_t>(r),
                              o.onset_s, o.long_integration, o.systems});
  return points;
}

std::vector<std::string> jam_point_command(const std::string& exe, const JamPoint& p, const std::string& out_dir) {
  std::vector<std::string> cmd = {exe,
                                  "-q",
                                  "bench",
                                  "jam-point",
                                  "--scenario",
                                  p.scenario,
                                  "--jammer",
                                  p.jammer,
                                  "--js",
                                  fmt::format("{}", p.js_db),
                                  "--mode",
                                  p.mode,
                                  "--mitigation",
                                  p.mitigation,
                                  "--seed",
                                  std::to_string(p.seed),
                                  "--onset",
                                  fmt::format("{}", p.onset_s),
                                  "--coherent-ms",
                                  std::to_string(p.long_integration.coherent_ms),
                                  "--noncoherent-ms",
                                  std::to_string(p.long_integration.noncoherent_ms)};
  if (p.long_integration.assist_data_bits) cmd.push_back("--assist-data-bits");
  if (!is_gps_only(p.systems)) {
    cmd.push_back("--systems");
    cmd.push_back(systems_list(p.systems));
  }
  cmd.push_back("--out");
  cmd.push_back(out_dir);
  return cmd;
}

void run_jam_sweep(const JamSweepSettings& o) {
  const std::vector<JamPoint> points = jam_sweep_points(o);
  const std::string exe = self_executable();
  const fs::path out = fs::absolute(o.out_dir);
  if (o.list_commands) {
    for (const auto& p : points)
      if (!point_done(out.string(), p)) fmt::print("{}\n", shell_command_line(jam_point_command(exe, p, out.string())));
    return;
  }
  if (o.jobs < 1) throw InputError("--jobs: expected at least 1");
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw InputError("cannot create output folder '" + out.string() + "': " + ec.message());
  std::vector<std::pair<JamPoint, std::vector<std::string>>> work;
  for (const auto& p : points)
    if (!point_done(out.string(), p)) work.emplace_back(p, jam_point_command(exe, p, out.string()));
  fmt::print("{} points: {} already finished in {}, {} to run with {} job(s)\n", points.size(),
             points.size() - work.size(), out.string(), work.size(), o.jobs);
  std::fflush(stdout);
  const int failed = run_parallel(work, out.string(), o.jobs);
  BenchReport report = write_jam_report(load_jam_points(out.string()), out.string());
  report.add_note("out", source_relative(out.string()));
  report.emit(o.json_path);
  if (!o.no_plots && run_plot_script("plot_jam.py", out.string())) spdlog::info("plots written to {}", out.string());
  if (failed > 0)
    throw InputError(fmt::format("{} point(s) failed to run; rerun the same command to retry them", failed));
}

}  // namespace deepnav::bench
