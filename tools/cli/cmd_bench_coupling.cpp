// `deepnav bench coupling`: paper 003 reproduced, in a chosen error world. Each trajectory
// (the four land and four aircraft paths, and the aircraft set with doubled rates/angles)
// is synthesized with an IMU of the paper's figures, then run through the receiver in
// loose, tight and ultra-tight mode; errors are the solutions' own against the
// synthesizer's truth (not filter covariances), over Monte Carlo runs with fixed seeds.
// Each (trajectory, run) is one seeded point whose result is kept in <out>/points/, so a
// sweep resumes where it stopped and its points can be run apart (--list-commands prints
// one command a point, for GNU parallel or a Slurm array). The report gives, per
// trajectory and mode, the mean and spread over runs of each run's RMS error, the 1-sigma
// error at 150 s beside the paper's figures, and whether ultra <= tight <= loose holds.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>

#include "signals/sim/error_presets.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/cli/atmosphere_options.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/child_process.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/progress.hpp"

#include <unistd.h>

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives
namespace {

namespace fs = std::filesystem;

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
  const auto it = std::find(all.begin(), all.end(), trajectory);
  if (it == all.end()) throw UserError("--trajectories: unknown trajectory '" + trajectory + "'");
  return static_cast<std::size_t>(it - all.begin());
}

struct CouplingOptions {
  std::vector<std::string> trajectories = all_trajectories();
  std::vector<std::string> modes{"loose", "tight", "ultra"};
  int runs = 2;
  int first_run = 0;
  double duration_s = 200.0;
  double score_at_s = 150.0;
  double score_from_s = 30.0;
  std::string imu_grade = "paper003";
  std::string errors = "none";
  std::string base_scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/land_circle_aided_90s.yaml";
  std::string work_dir, out_dir, json_path, csv_path, plot_path;
  unsigned jobs = 1;
  std::uint64_t seed = 300;
  bool list_commands = false;
  bool filter_troposphere = false;  ///< tight/ultra: the zenith troposphere residual state
  bool filter_ionosphere = false;   ///< tight/ultra: the ionosphere model's scale state
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

std::string point_name(const std::string& trajectory, int run) { return fmt::format("{}_r{:03d}", trajectory, run); }
fs::path point_path(const CouplingOptions& o, const std::string& trajectory, int run) {
  return fs::path(o.out_dir) / "points" / (point_name(trajectory, run) + ".json");
}

/// What a point's figures depend on besides (trajectory, run): a finished point made with
/// other settings must not be mixed into this table.
nlohmann::json point_settings(const CouplingOptions& o, const std::string& trajectory, int run) {
  nlohmann::json s = {{"trajectory", trajectory},     {"run", run},
          {"seed", o.seed + 1000 * static_cast<std::uint64_t>(run) + seed_index(trajectory)},
          {"errors", o.errors},           {"duration_s", o.duration_s},
          {"imu_grade", o.imu_grade},     {"scenario", source_relative(o.base_scenario)},
          {"receiver_ionosphere", to_string(o.atmosphere.ionosphere)},
          {"receiver_troposphere", to_string(o.atmosphere.troposphere)}};
  // Only when set, so points made before the option existed still match.
  if (o.filter_troposphere) s["filter_troposphere"] = true;
  if (o.filter_ionosphere) s["filter_ionosphere"] = true;
  return s;
}

/// One point: the trajectory synthesized in the chosen error world, every mode run on it.
nlohmann::json run_point(const CouplingOptions& o, const std::string& trajectory, int run) {
  const nlohmann::json settings = point_settings(o, trajectory, run);
  Scenario sc = load_scenario(o.base_scenario, DEEPNAV_SOURCE_DIR);
  sc.name = "coupling_" + point_name(trajectory, run) + "_" + o.errors;
  sc.trajectory.preset = trajectory;
  if (trajectory.rfind("air", 0) == 0) sc.trajectory.start.height_m = 1000.0;
  sc.duration_s = o.duration_s;
  sc.imu.enabled = true;
  sc.imu.grade = o.imu_grade;
  sc.seed = settings["seed"].get<std::uint64_t>();
  sc.errors = error_preset(o.errors);
  validate_scenario(sc);
  const std::string dir = (fs::path(o.work_dir) / sc.name).string();
  SynthesisOptions so;
  so.threads = 1;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir, so);
  // Aircraft turns ramp the Doppler by tens of Hz/s: third-order PLL for them.
  AidedRunSettings run_settings;
  run_settings.pll_order = trajectory.rfind("air", 0) == 0 ? 3 : 2;
  run_settings.atmosphere = o.atmosphere;
  run_settings.filter_troposphere = o.filter_troposphere;
  run_settings.filter_ionosphere = o.filter_ionosphere;
  nlohmann::json point = settings;
  for (const auto& m : o.modes) {
    const AidedRunResult r = run_aided_scenario(sc, s, aiding::parse_nav_mode(m), run_settings);
    nlohmann::json epochs = nlohmann::json::array();
    for (const auto& e : r.epochs)
      epochs.push_back({e.t_s, aiding::to_string(e.mode), e.valid, e.error_ned_m(0), e.error_ned_m(1), e.error_ned_m(2),
                        e.velocity_error_mps});
    point["modes"][m] = {{"epochs", epochs}, {"wall_s", r.wall_s}, {"satellite_exclusions", r.satellite_exclusions}};
    // Whether (and when) a model mismatch was found: what changed the filter's states.
    const auto when = [](const std::optional<double>& t) { return t ? nlohmann::json(*t) : nlohmann::json(nullptr); };
    point["modes"][m]["troposphere_mismatch_s"] = when(r.troposphere_mismatch_s);
    point["modes"][m]["ionosphere_mismatch_s"] = when(r.ionosphere_mismatch_s);
  }
  fs::remove_all(dir);
  return point;
}

void write_point(const CouplingOptions& o, const std::string& trajectory, int run, const nlohmann::json& point) {
  const fs::path path = point_path(o, trajectory, run);
  fs::create_directories(path.parent_path());
  TextOutputFile f(path.string());
  f.write(point.dump(1) + "\n");
  f.commit();
}

/// The finished point, or null; throws when it was made with other settings.
nlohmann::json load_point(const CouplingOptions& o, const std::string& trajectory, int run) {
  const fs::path path = point_path(o, trajectory, run);
  if (!fs::exists(path)) return nullptr;
  std::ifstream in(path);
  nlohmann::json p;
  try {
    p = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw UserError(fmt::format("{}: not a coupling point ({}); delete it to run the point again", path.string(), e.what()));
  }
  const nlohmann::json want = point_settings(o, trajectory, run);
  for (const auto& [key, value] : want.items())
    if (!p.contains(key) || p[key] != value)
      throw UserError(fmt::format("{}: made with {} = {}, this run asks for {}; use another --out", path.string(), key,
                                  p.contains(key) ? p[key].dump() : "nothing", value.dump()));
  for (const auto& m : o.modes)
    if (!p["modes"].contains(m))
      throw UserError(fmt::format("{}: has no '{}' run; use another --out or the point's modes", path.string(), m));
  return p;
}

/// One mode of one run, scored.
struct RunScore {
  double rms_h_m = NAN, rms_3d_m = NAN;
  std::optional<Eigen::Vector3d> error_at_m;
  double in_mode_s = 0.0, scored_s = 0.0;
};

RunScore score_run(const nlohmann::json& epochs, const std::string& mode, const CouplingOptions& o) {
  RunScore s;
  double sum_h = 0.0, sum_v = 0.0;
  int n = 0;
  for (const auto& e : epochs) {
    const double t = e[0].get<double>();
    if (t < o.score_from_s) continue;
    s.scored_s += 1.0;
    if (e[1].get<std::string>() == mode) s.in_mode_s += 1.0;
    if (!e[2].get<bool>()) continue;
    const Eigen::Vector3d err(e[3].get<double>(), e[4].get<double>(), e[5].get<double>());
    sum_h += err.head<2>().squaredNorm();
    sum_v += err(2) * err(2);
    ++n;
    if (std::abs(t - o.score_at_s) < 1e-6) s.error_at_m = err;
  }
  if (n > 0) {
    s.rms_h_m = std::sqrt(sum_h / n);
    s.rms_3d_m = std::sqrt((sum_h + sum_v) / n);
  }
  return s;
}

struct Spread {
  double mean = NAN, std = NAN;
  int n = 0;
};
Spread spread(const std::vector<double>& v) {
  Spread s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  double ss = 0.0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std = s.n > 1 ? std::sqrt(ss / (s.n - 1)) : 0.0;
  return s;
}

/// Whether `better` beats `worse` in the runs' paired differences: "yes" when the mean
/// difference is below zero by more than two standard errors, "no" when above by as
/// much, "tie" in between.
std::string paired_verdict(const std::vector<double>& better, const std::vector<double>& worse) {
  std::vector<double> d;
  for (std::size_t i = 0; i < std::min(better.size(), worse.size()); ++i) d.push_back(better[i] - worse[i]);
  const Spread s = spread(d);
  if (s.n < 2) return s.n == 1 ? (s.mean <= 0.0 ? "yes(1 run)" : "no(1 run)") : "n/a";
  const double se = s.std / std::sqrt(static_cast<double>(s.n));
  if (s.mean < -2.0 * se) return "yes";
  if (s.mean > 2.0 * se) return "no";
  return "tie";
}

void write_csv(const std::string& path, const std::vector<nlohmann::json>& points) {
  std::ofstream csv(path);
  if (!csv) throw UserError("cannot write '" + path + "'");
  csv << "trajectory,run,requested_mode,t_s,mode,valid,error_n_m,error_e_m,error_d_m,velocity_error_mps\n";
  for (const auto& p : points)
    for (const auto& [mode, r] : p["modes"].items())
      for (const auto& e : r["epochs"])
        csv << fmt::format("{},{},{},{:.2f},{},{},{:.4f},{:.4f},{:.4f},{:.4f}\n", p["trajectory"].get<std::string>(),
                           p["run"].get<int>(), mode, e[0].get<double>(), e[1].get<std::string>(), e[2].get<bool>() ? 1 : 0,
                           e[3].get<double>(), e[4].get<double>(), e[5].get<double>(), e[6].get<double>());
}

/// The command that runs one point alone (what --list-commands prints).
std::vector<std::string> point_command(const CouplingOptions& o, const std::string& trajectory, int run) {
  std::string modes;
  for (const auto& m : o.modes) modes += (modes.empty() ? "" : ",") + m;
  std::vector<std::string> cmd{self_executable(), "bench",      "coupling",          "--trajectories",
          trajectory,        "--first-run", std::to_string(run), "--runs",
          "1",               "--modes",     modes,               "--errors",
          o.errors,          "--duration",  fmt::format("{}", o.duration_s), "--imu-grade",
          o.imu_grade,       "--scenario",  o.base_scenario,     "--seed",
          std::to_string(o.seed), "--ionosphere", to_string(o.atmosphere.ionosphere), "--troposphere",
          to_string(o.atmosphere.troposphere), "--out", o.out_dir};
  if (o.filter_troposphere) cmd.push_back("--filter-troposphere");
  if (o.filter_ionosphere) cmd.push_back("--filter-ionosphere");
  return cmd;
}

/// Per mode, in how many points the aided filter found the troposphere or the ionosphere
/// model not to match the signal ("-": points written before that was recorded).
nlohmann::json mismatch_counts(const std::vector<nlohmann::json>& points, const std::vector<std::string>& modes) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& mode : modes) {
    int recorded = 0, troposphere = 0, ionosphere = 0;
    for (const auto& p : points) {
      const auto& m = p["modes"][mode];
      if (!m.contains("troposphere_mismatch_s")) continue;
      ++recorded;
      troposphere += m["troposphere_mismatch_s"].is_null() ? 0 : 1;
      ionosphere += m["ionosphere_mismatch_s"].is_null() ? 0 : 1;
    }
    out[mode] = recorded == 0 ? nlohmann::json("-")
                              : nlohmann::json(fmt::format("troposphere {} / ionosphere {} of {} runs", troposphere,
                                                           ionosphere, recorded));
  }
  return out;
}

void run_missing_points(const CouplingOptions& o, const std::vector<std::pair<std::string, int>>& todo) {
  ProgressLine progress("coupling", 0.0);
  std::mutex done_mutex;
  std::size_t done = 0;
  const unsigned jobs = std::max(1u, o.jobs);
  for (std::size_t first = 0; first < todo.size(); first += jobs) {
    std::vector<std::future<void>> batch;
    for (std::size_t k = first; k < std::min(todo.size(), first + jobs); ++k) {
      batch.push_back(std::async(std::launch::async, [&, k] {
        const auto& [trajectory, run] = todo[k];
        write_point(o, trajectory, run, run_point(o, trajectory, run));
        const std::lock_guard<std::mutex> lock(done_mutex);
        progress.update(static_cast<double>(++done) / static_cast<double>(todo.size()));
      }));
    }
    for (auto& f : batch) f.get();
  }
  progress.finish();
}

void run_coupling(CouplingOptions o) {
  if (o.runs < 1) throw UserError("--runs must be at least 1");
  if (o.first_run < 0) throw UserError("--first-run must be 0 or more");
  for (const auto& m : o.modes) {
    if (m != "loose" && m != "tight" && m != "ultra" && m != "scalar")
      throw UserError("--modes: unknown mode '" + m + "' (expected scalar, loose, tight, ultra)");
  }
  try {
    (void)error_preset(o.errors);
  } catch (const std::invalid_argument& e) {
    throw UserError(std::string("--errors: ") + e.what());
  }
  for (const auto& t : o.trajectories) (void)seed_index(t);
  if (o.score_at_s >= o.duration_s) throw UserError("--score-at must fall inside --duration");
  const bool own_work_dir = o.work_dir.empty();
  o.work_dir = bench_scratch_dir(o.work_dir, "bench_coupling");
  // Without --out the points live in a folder of their own that is removed afterwards.
  const bool keep_points = !o.out_dir.empty();
  if (!keep_points) o.out_dir = (fs::path(o.work_dir) / fmt::format("points_{}", getpid())).string();
  o.out_dir = fs::absolute(o.out_dir).string();

  std::vector<std::pair<std::string, int>> todo;
  for (const auto& t : o.trajectories)
    for (int r = o.first_run; r < o.first_run + o.runs; ++r)
      if (load_point(o, t, r).is_null()) todo.emplace_back(t, r);
  if (o.list_commands) {
    for (const auto& [t, r] : todo) fmt::print("{}\n", shell_command_line(point_command(o, t, r)));
    return;
  }
  if (keep_points) {
    spdlog::info("{} points, {} already finished in {}, {} to run", o.trajectories.size() * o.runs,
                 o.trajectories.size() * o.runs - todo.size(), o.out_dir, todo.size());
  }
  run_missing_points(o, todo);

  std::vector<nlohmann::json> points;
  for (const auto& t : o.trajectories)
    for (int r = o.first_run; r < o.first_run + o.runs; ++r) points.push_back(load_point(o, t, r));
  if (!keep_points) fs::remove_all(o.out_dir);
  std::error_code ignored;  // a folder of our own, empty by now (each point removes its IF)
  if (own_work_dir) fs::remove(o.work_dir, ignored);

  BenchReport report(fmt::format("GNSS/INS coupling: position error against truth (paper 003), errors: {}", o.errors),
                     {"trajectory", "mode", "n_at_m", "e_at_m", "d_at_m", "paper_n_m", "paper_e_m", "paper_d_m",
                      "rms_h_mean_m", "rms_h_std_m", "rms_3d_mean_m", "rms_3d_std_m", "in_mode_pct"});
  for (const char* c : {"n_at_m", "e_at_m", "d_at_m", "paper_n_m", "paper_e_m", "paper_d_m", "rms_h_mean_m", "rms_h_std_m",
                        "rms_3d_mean_m", "rms_3d_std_m"})
    report.set_precision(c, 3);
  report.set_precision("in_mode_pct", 0);
  int holds_h = 0, holds_3d = 0, checked = 0;
  nlohmann::json ordering = nlohmann::json::object();
  for (const auto& traj : o.trajectories) {
    std::map<std::string, std::vector<double>> per_run_h, per_run_3d;
    std::map<std::string, double> mean_h, mean_3d;
    for (const auto& mode : o.modes) {
      Eigen::Vector3d sum2_at = Eigen::Vector3d::Zero();
      int n_at = 0;
      double in_mode = 0.0, scored = 0.0;
      for (const auto& p : points) {
        if (p["trajectory"] != traj) continue;
        const RunScore s = score_run(p["modes"][mode]["epochs"], mode, o);
        per_run_h[mode].push_back(s.rms_h_m);
        per_run_3d[mode].push_back(s.rms_3d_m);
        if (s.error_at_m) {
          sum2_at += s.error_at_m->cwiseAbs2();
          ++n_at;
        }
        in_mode += s.in_mode_s;
        scored += s.scored_s;
      }
      const Eigen::Vector3d at = n_at ? Eigen::Vector3d((sum2_at / n_at).cwiseSqrt()) : Eigen::Vector3d::Constant(NAN);
      const Spread h = spread(per_run_h[mode]), d3 = spread(per_run_3d[mode]);
      mean_h[mode] = h.mean;
      mean_3d[mode] = d3.mean;
      const auto paper = paper_figures().find({traj, mode});
      const Eigen::Vector3d pf = paper == paper_figures().end() ? Eigen::Vector3d::Constant(NAN) : paper->second;
      report.add_row({traj, mode, at(0), at(1), at(2), pf(0), pf(1), pf(2), h.mean, h.std, d3.mean, d3.std,
                      scored > 0 ? 100.0 * in_mode / scored : 0.0});
    }
    if (mean_h.count("loose") && mean_h.count("tight") && mean_h.count("ultra")) {
      ++checked;
      const bool h_ok = mean_h["ultra"] <= mean_h["tight"] && mean_h["tight"] <= mean_h["loose"];
      const bool d3_ok = mean_3d["ultra"] <= mean_3d["tight"] && mean_3d["tight"] <= mean_3d["loose"];
      holds_h += h_ok ? 1 : 0;
      holds_3d += d3_ok ? 1 : 0;
      ordering[traj] = {{"horizontal", h_ok},
                        {"3d", d3_ok},
                        {"ultra_beats_tight_3d", paired_verdict(per_run_3d["ultra"], per_run_3d["tight"])},
                        {"tight_beats_loose_3d", paired_verdict(per_run_3d["tight"], per_run_3d["loose"])},
                        {"ultra_beats_loose_3d", paired_verdict(per_run_3d["ultra"], per_run_3d["loose"])}};
    }
  }
  report.add_note("runs", o.runs);
  report.add_note("errors", o.errors);
  report.add_note("imu_grade", o.imu_grade);
  report.add_note("scenario", source_relative(o.base_scenario));
  report.add_note("receiver_models", fmt::format("ionosphere {}, troposphere {}{}{}", to_string(o.atmosphere.ionosphere),
                                                 to_string(o.atmosphere.troposphere),
                                                 o.filter_troposphere ? ", zenith troposphere state" : "",
                                                 o.filter_ionosphere ? ", ionosphere scale state" : ""));
  report.add_note("scoring", fmt::format("n/e/d_at: north/east/down 1-sigma over runs at t = {} s (RMS across runs); "
                                         "rms_h/rms_3d: each run's RMS over every epoch from {} s to {} s, mean and "
                                         "standard deviation over the runs",
                                         o.score_at_s, o.score_from_s, o.duration_s));
  report.add_note("ordering_ultra_le_tight_le_loose_horizontal", fmt::format("{} of {} trajectories", holds_h, checked));
  report.add_note("ordering_ultra_le_tight_le_loose_3d", fmt::format("{} of {} trajectories", holds_3d, checked));
  report.add_note("paired_3d", ordering);
  report.add_note("mismatch_found", mismatch_counts(points, o.modes));
  if (keep_points) report.add_note("out", source_relative(o.out_dir));
  report.emit(o.json_path);
  if (!o.csv_path.empty()) write_csv(o.csv_path, points);
  if (!o.plot_path.empty()) {
    if (o.csv_path.empty()) throw UserError("--plot needs --csv (the plot is drawn from it)");
    const std::string cmd = fmt::format("/usr/bin/python3 {}/tools/plots/plot_coupling.py '{}' '{}'", DEEPNAV_SOURCE_DIR,
                                        o.csv_path, o.plot_path);
    if (std::system(cmd.c_str()) != 0) throw UserError("plotting failed: " + cmd);
  }
}

}  // namespace

void add_bench_coupling_command(CommandParents& parents) {
  auto o = std::make_shared<CouplingOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("coupling", "Paper 003: loose/tight/ultra-tight position errors per trajectory");
  cmd->add_option("--trajectories", o->trajectories, "Trajectory presets")->delimiter(',')->capture_default_str();
  cmd->add_option("--modes", o->modes, "Modes")->delimiter(',')->capture_default_str();
  cmd->add_option("--runs", o->runs, "Monte Carlo runs per trajectory (seeds fixed)")->capture_default_str();
  cmd->add_option("--first-run", o->first_run, "Index of the first run (a slice of a larger sweep)")->capture_default_str();
  cmd->add_option("--errors", o->errors, "Error world preset: none, open-sky, suburban, urban")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Scenario length (s)")->capture_default_str();
  cmd->add_option("--score-at", o->score_at_s, "Time of the 1-sigma figures (s)")->capture_default_str();
  cmd->add_option("--imu-grade", o->imu_grade, "IMU grade (data/imu_grades.yaml)")->capture_default_str();
  cmd->add_option("--scenario", o->base_scenario, "Base scenario (signal, clock, IMU lever arm)")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Base seed")->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "Scenarios run at once")->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Folder of finished points (points/*.json): a rerun resumes from it");
  cmd->add_flag("--filter-troposphere", o->filter_troposphere,
                 "Tight and ultra-tight: estimate a zenith troposphere residual (an 18th state)");
  cmd->add_flag("--filter-ionosphere", o->filter_ionosphere,
                "Tight and ultra-tight: estimate the ionosphere model's scale error (a 19th state)");
  cmd->add_flag("--list-commands", o->list_commands, "Print one command per unfinished point and stop");
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF files are written");
  cmd->add_option("--csv", o->csv_path, "Per-epoch errors of every run");
  cmd->add_option("--plot", o->plot_path, "PNG of error over time for the circle cases (needs --csv)");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  add_atmosphere_options(*cmd, o->atmosphere);
  cmd->callback([o] { run_coupling(*o); });
}

}  // namespace deepnav::cli
