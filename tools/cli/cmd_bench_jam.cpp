// `deepnav bench jam`: J/S sweeps of one scenario under CW, chirp, wideband and pulsed
// jammers, for every receiver mode and mitigation asked for. Each point (scenario,
// jammer, J/S, mode, mitigation, seed) is one deterministic command,
// `deepnav bench jam-point ...`; the sweep runs the unfinished ones in parallel
// (--jobs), skips those already in --out (resume), prints them instead with
// --list-commands (GNU parallel, a Slurm array), and then reports over every finished
// point in --out: runs.csv, thresholds.md and PNG plots.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "receiver/mitigation/mitigation_config.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/child_process.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/long_integration_options.hpp"
#include "tools/bench/jam_point.hpp"
#include "tools/bench/jam_report.hpp"
#include "tools/bench/python_plot.hpp"
#include "tools/bench/receiver_modes.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives
namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/jam_static_32s.yaml";
  std::string jammers = "cw";
  std::string js = "20:60:5";
  std::string modes = "scalar";
  std::string mitigations = "none,auto";
  int runs = 1;
  double onset_s = 16.0;
  std::string out_dir;
  int jobs = 1;
  bool list_commands = false;
  bool no_plots = false;
  std::string json_path;
  aiding::LongIntegrationConfig long_integration;
};

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ','))
    if (!item.empty()) out.push_back(item);
  if (out.empty()) throw UserError(option + ": expected a comma-separated list, got '" + text + "'");
  return out;
}

/// FROM:TO:STEP (or one value) in dB.
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
    throw UserError("--js '" + text + "': expected FROM:TO:STEP in dB (e.g. 20:60:5) or one value");
  }
  if (parts.size() == 1) parts = {parts[0], parts[0], 1.0};
  if (parts.size() != 3 || !(parts[2] > 0.0) || !(parts[1] >= parts[0]) || parts[0] < -50.0 || parts[1] > 120.0)
    throw UserError("--js '" + text + "': expected FROM:TO:STEP with FROM <= TO within [-50, 120] dB and STEP > 0");
  std::vector<double> values;
  for (int k = 0;; ++k) {
    const double v = parts[0] + k * parts[2];
    if (v > parts[1] + 1e-9) break;
    values.push_back(std::round(v * 10.0) / 10.0);
  }
  return values;
}

std::vector<JamPoint> sweep_points(const SweepOptions& o) {
  Scenario base;
  try {
    base = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  } catch (const std::exception& e) {
    throw UserError(e.what());
  }
  const auto jammers = split_list(o.jammers, "--jammer");
  for (const auto& j : jammers) benchmark_jammer(j, 0.0, 0.0);  // rejects unknown types
  const auto modes = split_list(o.modes, "--modes");
  for (const auto& m : modes)
    if (find_receiver_mode(m).needs_imu && !base.imu.enabled)
      throw UserError(fmt::format("--modes {}: mode '{}' needs an IMU, but scenario '{}' has no imu: section "
                                  "(e.g. imu: {{grade: tactical, rate_hz: 100}})",
                                  o.modes, m, o.scenario));
  const auto mitigations = split_list(o.mitigations, "--mitigation");
  for (const auto& m : mitigations) {
    try {
      parse_mitigation_mode(m);
    } catch (const std::invalid_argument& e) {
      throw UserError(std::string("--mitigation: ") + e.what());
    }
  }
  if (o.runs < 1) throw UserError("--runs: expected at least 1");
  if (!(o.onset_s >= 0.0 && o.onset_s < base.duration_s))
    throw UserError(fmt::format("--onset {} s: expected within the scenario's {} s", o.onset_s, base.duration_s));
  std::vector<JamPoint> points;
  for (const auto& jammer : jammers)
    for (const auto& mode : modes)
      for (const auto& mitigation : mitigations)
        for (int r = 0; r < o.runs; ++r)
          for (double js : parse_js_range(o.js))
            points.push_back({o.scenario, jammer, js, mode, mitigation, base.seed + static_cast<std::uint64_t>(r),
                              o.onset_s, o.long_integration});
  return points;
}

std::vector<std::string> point_command(const std::string& exe, const JamPoint& p, const std::string& out_dir) {
  std::vector<std::string> cmd = {exe,          "-q",       "bench",          "jam-point",        "--scenario",    p.scenario,
          "--jammer",   p.jammer,   "--js",           fmt::format("{}", p.js_db), "--mode", p.mode,
          "--mitigation", p.mitigation, "--seed",     std::to_string(p.seed), "--onset", fmt::format("{}", p.onset_s),
          "--coherent-ms", std::to_string(p.long_integration.coherent_ms),
          "--noncoherent-ms", std::to_string(p.long_integration.noncoherent_ms), "--out", out_dir};
  if (p.long_integration.assist_data_bits) cmd.insert(cmd.end() - 2, "--assist-data-bits");
  return cmd;
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
    fmt::print("[{}/{}] {} {}\n", done, work.size(), point_id(p),
               status == 0 ? "done" : fmt::format("FAILED (exit {}, see {}/{}.log)", status, logs.string(), point_id(p)));
    std::fflush(stdout);
    running.erase(it);
  }
  return failed;
}

void run_sweep(const SweepOptions& o) {
  const std::vector<JamPoint> points = sweep_points(o);
  const std::string exe = self_executable();
  const fs::path out = fs::absolute(o.out_dir);
  if (o.list_commands) {
    for (const auto& p : points)
      if (!point_done(out.string(), p)) fmt::print("{}\n", shell_command_line(point_command(exe, p, out.string())));
    return;
  }
  if (o.jobs < 1) throw UserError("--jobs: expected at least 1");
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw UserError("cannot create output folder '" + out.string() + "': " + ec.message());
  std::vector<std::pair<JamPoint, std::vector<std::string>>> work;
  for (const auto& p : points)
    if (!point_done(out.string(), p)) work.emplace_back(p, point_command(exe, p, out.string()));
  fmt::print("{} points: {} already finished in {}, {} to run with {} job(s)\n", points.size(),
             points.size() - work.size(), out.string(), work.size(), o.jobs);
  std::fflush(stdout);
  const int failed = run_parallel(work, out.string(), o.jobs);
  BenchReport report = write_jam_report(load_jam_points(out.string()), out.string());
  report.add_note("out", source_relative(out.string()));
  report.emit(o.json_path);
  if (!o.no_plots && run_plot_script("plot_jam.py", out.string())) spdlog::info("plots written to {}", out.string());
  if (failed > 0) throw UserError(fmt::format("{} point(s) failed to run; rerun the same command to retry them", failed));
}

}  // namespace

void add_bench_jam_command(CommandParents& parents) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "jam", "Jamming sweep: J/S thresholds per jammer, receiver mode and mitigation (CSV, table, plots)");
  cmd->add_option("--scenario", o->scenario, "Base scenario (the jammer is added from --onset)")->capture_default_str();
  cmd->add_option("--jammer", o->jammers, "cw, chirp, wideband, pulsed (comma-separated list)")->capture_default_str();
  cmd->add_option("--js", o->js, "J/S sweep FROM:TO:STEP (dB)")->capture_default_str();
  std::string mode_names;
  for (const auto& m : receiver_modes()) mode_names += (mode_names.empty() ? "" : ", ") + m.name;
  cmd->add_option("--modes", o->modes, "Receiver modes (available: " + mode_names + ")")->capture_default_str();
  cmd->add_option("--mitigation", o->mitigations, "Mitigations: none, notch, excision, blanking, auto (list)")
      ->capture_default_str();
  cmd->add_option("--runs", o->runs, "Seeds per point (scenario seed, +1, ...)")->capture_default_str();
  cmd->add_option("--onset", o->onset_s, "Jammer onset (s); the figures cover onset to end")->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Sweep folder (points/, runs.csv, thresholds.md, PNGs)")->required();
  cmd->add_option("--jobs", o->jobs, "Points run at the same time")->capture_default_str();
  add_long_integration_options(*cmd, o->long_integration);
  cmd->add_flag("--list-commands", o->list_commands, "Print the unfinished points' commands, one a line, and stop");
  cmd->add_flag("--no-plots", o->no_plots, "Skip the PNG plots");
  cmd->add_option("--json", o->json_path, "Write the threshold table as JSON to this file");
  cmd->callback([o] { run_sweep(*o); });

  auto p = std::make_shared<JamPoint>();
  auto out = std::make_shared<std::string>();
  CLI::App* point = parents.bench.add_subcommand("jam-point", "One point of `deepnav bench jam` (writes OUT/points/ID/point.json)");
  point->add_option("--scenario", p->scenario, "Base scenario")->required();
  point->add_option("--jammer", p->jammer, "cw, chirp, wideband, pulsed")->required();
  point->add_option("--js", p->js_db, "J/S (dB)")->required();
  point->add_option("--mode", p->mode, "Receiver mode")->capture_default_str();
  point->add_option("--mitigation", p->mitigation, "none, notch, excision, blanking, auto")
      ->check(CLI::IsMember(mitigation_mode_names()))
      ->capture_default_str();
  point->add_option("--seed", p->seed, "Seed of noise and jammer")->capture_default_str();
  point->add_option("--onset", p->onset_s, "Jammer onset (s)")->capture_default_str();
  add_long_integration_options(*point, p->long_integration);
  point->add_option("--out", *out, "Sweep folder")->required();
  point->callback([p, out] {
    const auto fig = run_jam_point(*p, fs::absolute(*out).string());
    fmt::print("{}: tracked {:.2f}, C/N0 {}, fixes {:.2f}, horizontal max {} m -> {}\n", fig["id"].get<std::string>(),
               fig["tracked_fraction_mean"].get<double>(), fig["cn0_mean_dbhz"].dump(),
               fig["solution"]["fix_availability"].get<double>(), fig["solution"]["horizontal_max_m"].dump(),
               fig["failed"].get<bool>() ? "FAIL (" + fig["failure"].get<std::string>() + ")" : "ok");
  });
}

}  // namespace deepnav::cli
