// `deepnav bench coupling`: paper 003 reproduced. Each trajectory (the four land and
// four aircraft paths, and the aircraft set with doubled rates/angles) is synthesized
// with an IMU of the paper's figures, then run through the receiver in loose, tight and
// ultra-tight mode; errors are the solutions' own against the synthesizer's truth (not
// filter covariances), over Monte Carlo runs with fixed seeds. Printed beside the paper's
// 1-sigma errors at 150 s; per-epoch errors go to a CSV and a PNG of the circle cases.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <mutex>

#include "signals/rinex_nav.hpp"
#include "tools/aided_scenario_run.hpp"
#include "tools/atmosphere_options.hpp"
#include "tools/bench_report.hpp"
#include "tools/command_registry.hpp"
#include "tools/progress.hpp"

namespace deepnav::cli {
namespace {

const std::vector<std::string>& all_trajectories() {
  static const std::vector<std::string> t{"land-straight", "land-accel",   "land-circle",   "land-s",
                                          "air-circle",    "air-s",        "air-spiral",    "air-wingrock",
                                          "air-circle-x2", "air-s-x2",     "air-spiral-x2", "air-wingrock-x2"};
  return t;
}

/// A trajectory's place in the full list: its scenarios' seeds do not depend on which other
/// trajectories a run names, so a subset reproduces the full table's rows.
std::size_t seed_index(const std::string& trajectory) {
  const auto& all = all_trajectories();
  return static_cast<std::size_t>(std::find(all.begin(), all.end(), trajectory) - all.begin());
}

struct CouplingOptions {
  std::vector<std::string> trajectories = all_trajectories();
  std::vector<std::string> modes{"loose", "tight", "ultra"};
  int runs = 2;
  double duration_s = 200.0;
  double score_at_s = 150.0;
  double score_from_s = 30.0;
  std::string imu_grade = "paper003";
  std::string base_scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/land_circle_aided_90s.yaml";
  std::string work_dir, json_path, csv_path, plot_path;
  unsigned jobs = 1;
  std::uint64_t seed = 300;
  AtmosphereModels atmosphere;  ///< the receiver's (the scenario decides what is synthesized)
};

/// Paper 003's 1-sigma position errors at 150 s (m, x/y/z), where the paper states them.
const std::map<std::pair<std::string, std::string>, Eigen::Vector3d>& paper_figures() {
  static const std::map<std::pair<std::string, std::string>, Eigen::Vector3d> f{
      {{"land-circle", "tight"}, {2.384, 3.251, 1.455}},
      {{"land-circle", "ultra"}, {0.430, 1.015, 0.906}},
      {{"air-circle", "loose"}, {1.783, 2.429, 5.512}},
      {{"air-circle", "tight"}, {1.248, 1.177, 3.881}},
      {{"air-circle", "ultra"}, {0.591, 0.634, 0.896}},
  };
  return f;
}

struct UnitResult {
  std::string trajectory;
  int run = 0;
  std::map<std::string, AidedRunResult> by_mode;
};

UnitResult run_unit(const CouplingOptions& o, const std::string& trajectory, int run, std::size_t index) {
  Scenario sc = load_scenario(o.base_scenario, DEEPNAV_SOURCE_DIR);
  sc.name = fmt::format("coupling_{}_{}", trajectory, run);
  sc.trajectory.preset = trajectory;
  if (trajectory.rfind("air", 0) == 0) sc.trajectory.start.height_m = 1000.0;
  sc.duration_s = o.duration_s;
  sc.imu.enabled = true;
  sc.imu.grade = o.imu_grade;
  sc.seed = o.seed + 1000 * static_cast<std::uint64_t>(run) + index;
  validate_scenario(sc);
  const std::string dir = (std::filesystem::path(o.work_dir) / sc.name).string();
  SynthesisOptions so;
  so.threads = 1;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir, so);
  UnitResult u{trajectory, run, {}};
  // Aircraft turns ramp the Doppler by tens of Hz/s: third-order PLL for them.
  const int pll_order = trajectory.rfind("air", 0) == 0 ? 3 : 2;
  for (const auto& m : o.modes)
    u.by_mode[m] = run_aided_scenario(sc, s, aiding::parse_nav_mode(m), pll_order, o.atmosphere);
  std::filesystem::remove_all(dir);
  return u;
}

struct Accumulator {
  Eigen::Vector3d sum2_at = Eigen::Vector3d::Zero();
  int n_at = 0;
  double sum2_h = 0.0, sum2_v = 0.0;
  int n_run = 0;
  double time_in_mode = 0.0, time_total = 0.0;
};

void write_csv(const std::string& path, const std::vector<UnitResult>& units) {
  std::ofstream csv(path);
  if (!csv) throw UserError("cannot write '" + path + "'");
  csv << "trajectory,run,requested_mode,t_s,mode,valid,error_n_m,error_e_m,error_d_m,velocity_error_mps\n";
  for (const auto& u : units)
    for (const auto& [mode, r] : u.by_mode)
      for (const auto& e : r.epochs)
        csv << fmt::format("{},{},{},{:.2f},{},{},{:.4f},{:.4f},{:.4f},{:.4f}\n", u.trajectory, u.run, mode, e.t_s,
                           aiding::to_string(e.mode), e.valid ? 1 : 0, e.error_ned_m(0), e.error_ned_m(1),
                           e.error_ned_m(2), e.velocity_error_mps);
}

void run_coupling(CouplingOptions o) {
  if (o.runs < 1) throw UserError("--runs must be at least 1");
  for (const auto& m : o.modes) {
    if (m != "loose" && m != "tight" && m != "ultra" && m != "scalar")
      throw UserError("--modes: unknown mode '" + m + "' (expected scalar, loose, tight, ultra)");
  }
  if (o.score_at_s >= o.duration_s) throw UserError("--score-at must fall inside --duration");
  if (o.work_dir.empty()) o.work_dir = (std::filesystem::temp_directory_path() / "deepnav_bench_coupling").string();
  struct Task {
    std::string trajectory;
    int run;
    std::size_t index;
  };
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < o.trajectories.size(); ++i)
    for (int r = 0; r < o.runs; ++r) tasks.push_back({o.trajectories[i], r, seed_index(o.trajectories[i])});
  ProgressLine progress("coupling", 0.0);
  std::vector<UnitResult> units(tasks.size());
  std::mutex done_mutex;
  std::size_t done = 0;
  const unsigned jobs = std::max(1u, o.jobs);
  for (std::size_t first = 0; first < tasks.size(); first += jobs) {
    std::vector<std::future<void>> batch;
    for (std::size_t k = first; k < std::min(tasks.size(), first + jobs); ++k) {
      batch.push_back(std::async(std::launch::async, [&, k] {
        units[k] = run_unit(o, tasks[k].trajectory, tasks[k].run, tasks[k].index);
        const std::lock_guard<std::mutex> lock(done_mutex);
        progress.update(static_cast<double>(++done) / static_cast<double>(tasks.size()));
      }));
    }
    for (auto& f : batch) f.get();
  }
  progress.finish();

  std::map<std::pair<std::string, std::string>, Accumulator> acc;
  for (const auto& u : units) {
    for (const auto& [mode, r] : u.by_mode) {
      Accumulator& a = acc[{u.trajectory, mode}];
      const aiding::NavMode wanted = aiding::parse_nav_mode(mode);
      for (const auto& e : r.epochs) {
        if (e.t_s < o.score_from_s) continue;
        a.time_total += 1.0;
        if (e.mode == wanted) a.time_in_mode += 1.0;
        if (!e.valid) continue;
        a.sum2_h += e.error_ned_m.head<2>().squaredNorm();
        a.sum2_v += e.error_ned_m(2) * e.error_ned_m(2);
        ++a.n_run;
        if (std::abs(e.t_s - o.score_at_s) < 1e-6) {
          a.sum2_at += e.error_ned_m.cwiseAbs2();
          ++a.n_at;
        }
      }
    }
  }
  BenchReport report("GNSS/INS coupling: position error against truth (paper 003)",
                     {"trajectory", "mode", "n_at_m", "e_at_m", "d_at_m", "paper_n_m", "paper_e_m", "paper_d_m",
                      "rms_h_m", "rms_v_m", "in_mode_pct"});
  for (const char* c : {"n_at_m", "e_at_m", "d_at_m", "paper_n_m", "paper_e_m", "paper_d_m", "rms_h_m", "rms_v_m"})
    report.set_precision(c, 3);
  report.set_precision("in_mode_pct", 0);
  int ordering_holds = 0, ordering_checked = 0;
  for (const auto& traj : o.trajectories) {
    std::map<std::string, double> rms3;
    for (const auto& mode : o.modes) {
      const Accumulator& a = acc[{traj, mode}];
      const Eigen::Vector3d at = a.n_at ? Eigen::Vector3d((a.sum2_at / a.n_at).cwiseSqrt()) : Eigen::Vector3d::Constant(NAN);
      const double h = a.n_run ? std::sqrt(a.sum2_h / a.n_run) : NAN, v = a.n_run ? std::sqrt(a.sum2_v / a.n_run) : NAN;
      rms3[mode] = std::hypot(h, v);
      const auto p = paper_figures().find({traj, mode});
      const Eigen::Vector3d paper = p == paper_figures().end() ? Eigen::Vector3d::Constant(NAN) : p->second;
      report.add_row({traj, mode, at(0), at(1), at(2), paper(0), paper(1), paper(2), h, v,
                      a.time_total > 0 ? 100.0 * a.time_in_mode / a.time_total : 0.0});
    }
    if (rms3.count("loose") && rms3.count("tight") && rms3.count("ultra")) {
      ++ordering_checked;
      if (rms3["ultra"] < rms3["tight"] && rms3["tight"] < rms3["loose"]) ++ordering_holds;
    }
  }
  report.add_note("runs", o.runs);
  report.add_note("imu_grade", o.imu_grade);
  report.add_note("scoring", fmt::format("x/y/z columns: north/east/down 1-sigma over runs at t = {} s (RMS across runs); "
                                         "rms_h/rms_v over every epoch from {} s to {} s",
                                         o.score_at_s, o.score_from_s, o.duration_s));
  report.add_note("ordering_ultra_lt_tight_lt_loose", fmt::format("{} of {} trajectories", ordering_holds, ordering_checked));
  report.emit(o.json_path);
  if (!o.csv_path.empty()) write_csv(o.csv_path, units);
  if (!o.plot_path.empty()) {
    if (o.csv_path.empty()) throw UserError("--plot needs --csv (the plot is drawn from it)");
    const std::string cmd = fmt::format("/usr/bin/python3 {}/tools/plot_coupling.py '{}' '{}'", DEEPNAV_SOURCE_DIR,
                                        o.csv_path, o.plot_path);
    if (std::system(cmd.c_str()) != 0) throw UserError("plotting failed: " + cmd);
  }
}

const bool registered = register_command([](CommandParents& parents) {
  auto o = std::make_shared<CouplingOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("coupling", "Paper 003: loose/tight/ultra-tight position errors per trajectory");
  cmd->add_option("--trajectories", o->trajectories, "Trajectory presets")->delimiter(',')->capture_default_str();
  cmd->add_option("--modes", o->modes, "Modes")->delimiter(',')->capture_default_str();
  cmd->add_option("--runs", o->runs, "Monte Carlo runs per trajectory (seeds fixed)")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Scenario length (s)")->capture_default_str();
  cmd->add_option("--score-at", o->score_at_s, "Time of the 1-sigma figures (s)")->capture_default_str();
  cmd->add_option("--imu-grade", o->imu_grade, "IMU grade (data/imu_grades.yaml)")->capture_default_str();
  cmd->add_option("--scenario", o->base_scenario, "Base scenario (signal, clock, IMU lever arm)")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Base seed")->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "Scenarios run at once")->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF files are written");
  cmd->add_option("--csv", o->csv_path, "Per-epoch errors of every run");
  cmd->add_option("--plot", o->plot_path, "PNG of error over time for the circle cases (needs --csv)");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  add_atmosphere_options(*cmd, o->atmosphere);
  cmd->callback([o] { run_coupling(*o); });
});

}  // namespace
}  // namespace deepnav::cli
