#include "tools/bench/snapshot_bench.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>

#include "ins/frames.hpp"
#include "ins/input_error.hpp"
#include "ins/sim/trajectory_presets.hpp"
#include "receiver/snapshot_positioner.hpp"
#include "receiver/sources/sample_converter.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/python_plot.hpp"

namespace deepnav::bench {
namespace {

/// One snapshot point of a scenario: its samples (the longest length), truth and hints.
struct SnapshotPoint {
  double t_s = 0.0;  ///< after the scenario's first sample
  std::vector<Sample> samples;
  Eigen::Vector3d truth_ecef_m = Eigen::Vector3d::Zero();
  double time_error_s = 0.0;
  std::optional<Eigen::Vector3d> position_hint;
};

struct Outcome {
  std::string scenario;
  int length_ms = 0;
  int point = 0;
  double time_error_s = 0.0;
  bool solved = false;
  double horizontal_error_m = 0.0;
  double cpu_ms = 0.0;
  std::string reason;
};

double horizontal_m(const Eigen::Vector3d& fix, const Eigen::Vector3d& truth) {
  const wgs84::Llh llh = wgs84::ecef_to_llh(truth);
  const Eigen::Vector3d ned = C_e_n(llh.lat_rad, llh.lon_rad) * (fix - truth);
  return std::hypot(ned.x(), ned.y());
}

/// `r` moved over the ellipsoid by `distance_m` towards `azimuth_rad` (locally flat).
Eigen::Vector3d moved(const Eigen::Vector3d& r, double distance_m, double azimuth_rad) {
  wgs84::Llh llh = wgs84::ecef_to_llh(r);
  llh.lat_rad += distance_m * std::cos(azimuth_rad) / wgs84::meridian_radius_m(llh.lat_rad);
  llh.lon_rad += distance_m * std::sin(azimuth_rad) / (wgs84::transverse_radius_m(llh.lat_rad) * std::cos(llh.lat_rad));
  return wgs84::llh_to_ecef(llh);
}

/// The points' times: spread evenly over the run, each on a whole millisecond, with room
/// for the longest snapshot.
std::vector<double> point_times(double duration_s, int points, int longest_ms) {
  std::vector<double> times;
  const double usable_s = duration_s - longest_ms * 1e-3;
  for (int k = 0; k < points; ++k) times.push_back(std::floor((k + 0.5) * usable_s / points * 1e3) / 1e3);
  return times;
}

/// Synthesizes `sc` chunk by chunk and keeps `samples_per_point` samples from each point.
std::vector<SnapshotPoint> cut_points(const Scenario& sc, const NavData& nav, const std::vector<double>& times,
                                      std::size_t samples_per_point) {
  const IfSynthesizer synthesizer(sc, nav);
  const std::unique_ptr<IfChunkGenerator> generator = synthesizer.chunk_generator(0);
  const SampleConverter converter(sc.format, false);
  const std::size_t bytes_per = bytes_per_sample(sc.format);
  std::vector<SnapshotPoint> points(times.size());
  std::vector<std::byte> chunk;
  std::vector<Sample> samples;
  while (true) {
    const std::int64_t first = generator->next_sample_index();
    if (!generator->next(chunk)) break;
    samples.resize(chunk.size() / bytes_per);
    converter.convert(chunk, samples, first);
    const auto last = first + static_cast<std::int64_t>(samples.size());
    for (std::size_t k = 0; k < times.size(); ++k) {
      const auto start = static_cast<std::int64_t>(std::llround(times[k] * sc.sample_rate_hz));
      auto& kept = points[k].samples;
      const std::int64_t want_from = start + static_cast<std::int64_t>(kept.size());
      if (kept.size() >= samples_per_point || want_from >= last || want_from < first) continue;
      const auto take =
          std::min<std::int64_t>(last - want_from, static_cast<std::int64_t>(samples_per_point - kept.size()));
      kept.insert(kept.end(), samples.begin() + (want_from - first), samples.begin() + (want_from - first + take));
    }
  }
  return points;
}

std::vector<SnapshotPoint> scenario_points(const Scenario& sc, const NavData& nav, const SnapshotBenchSettings& s,
                                           std::mt19937_64& rng) {
  const int longest_ms = *std::max_element(s.lengths_ms.begin(), s.lengths_ms.end());
  const std::vector<double> times = point_times(sc.duration_s, s.points, longest_ms);
  const auto per_point = static_cast<std::size_t>(std::llround(longest_ms * 1e-3 * sc.sample_rate_hz));
  std::vector<SnapshotPoint> points = cut_points(sc, nav, times, per_point);
  const auto trajectory =
      make_preset_trajectory(sc.trajectory.preset, sc.trajectory.start, sc.trajectory.heading_rad, sc.duration_s);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    SnapshotPoint& p = points[k];
    p.t_s = times[k];
    p.truth_ecef_m = trajectory->at(p.t_s).r_ecef_m;
    p.time_error_s = s.max_time_error_s * unit(rng) * (unit(rng) < 0.5 ? -1.0 : 1.0);
    const double offset_m = s.max_hint_offset_m * unit(rng), azimuth = 2.0 * std::numbers::pi * unit(rng);
    if (s.position_hint) p.position_hint = moved(p.truth_ecef_m, offset_m, azimuth);
  }
  return points;
}

Scenario bench_scenario(const std::string& path, double cn0_dbhz) {
  Scenario sc = load_scenario(path, DEEPNAV_SOURCE_DIR);
  if (sc.trajectory.preset.empty())
    throw InputError(
        fmt::format("{}: the snapshot benchmark needs a preset trajectory (static, land-circle...)", path));
  sc.cn0.model = Cn0Spec::Model::fixed;
  sc.cn0.fixed_dbhz = cn0_dbhz;
  return sc;
}

std::vector<Outcome> solve_points(const std::string& name, const Scenario& sc, const NavData& nav,
                                  const std::vector<SnapshotPoint>& points, const SnapshotBenchSettings& s) {
  std::vector<Outcome> out;
  for (const int length_ms : s.lengths_ms) {
    SnapshotPositionerConfig config;
    config.sample_rate_hz = sc.sample_rate_hz;
    config.if_hz = sc.if_hz;
    config.snapshot_ms = length_ms;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const SnapshotPoint& p = points[k];
      SnapshotPositioner positioner(config, nav, p.position_hint);
      const GpsTime t_hint = sc.start_time.plus_seconds(p.t_s + p.time_error_s);
      const std::clock_t began = std::clock();
      const SnapshotResult r = positioner.solve(p.samples, t_hint);
      Outcome o{name,
                length_ms,
                static_cast<int>(k),
                p.time_error_s,
                r.fix.valid,
                0.0,
                1e3 * static_cast<double>(std::clock() - began) / CLOCKS_PER_SEC,
                r.fix.reason};
      if (o.solved) o.horizontal_error_m = horizontal_m(r.fix.r_ecef_m, p.truth_ecef_m);
      out.push_back(std::move(o));
    }
  }
  return out;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void add_row(BenchReport& report, const std::string& scenario, int length_ms, const std::vector<Outcome>& outcomes) {
  std::vector<double> errors, cpu;
  long long tried = 0;
  for (const Outcome& o : outcomes) {
    if (o.length_ms != length_ms || (scenario != "all" && o.scenario != scenario)) continue;
    ++tried;
    cpu.push_back(o.cpu_ms);
    if (o.solved) errors.push_back(o.horizontal_error_m);
  }
  report.add_row({scenario, static_cast<long long>(length_ms), static_cast<long long>(errors.size()), tried,
                  median(errors), quantile(errors, 0.95),
                  errors.empty() ? std::nan("") : *std::max_element(errors.begin(), errors.end()), median(cpu)});
}

nlohmann::json outcomes_json(const std::vector<Outcome>& outcomes) {
  nlohmann::json all = nlohmann::json::array();
  for (const Outcome& o : outcomes)
    all.push_back({{"scenario", o.scenario},
                   {"length_ms", o.length_ms},
                   {"point", o.point},
                   {"time_error_s", o.time_error_s},
                   {"solved", o.solved},
                   {"horizontal_error_m", o.solved ? nlohmann::json(o.horizontal_error_m) : nlohmann::json(nullptr)},
                   {"cpu_ms", o.cpu_ms},
                   {"reason", o.reason}});
  return all;
}

}  // namespace

void run_snapshot_bench(const SnapshotBenchSettings& s) {
  if (s.points < 1 || s.lengths_ms.empty()) throw InputError("bench snapshot: give at least one point and one length");
  for (const int l : s.lengths_ms)
    if (l < 2 || l > 100) throw InputError(fmt::format("bench snapshot: --lengths {} ms is outside 2..100 ms", l));
  std::vector<std::string> scenarios = s.scenarios;
  if (scenarios.empty())
    scenarios = {source_tree_path("data/scenarios/static_120s.yaml"),
                 source_tree_path("data/scenarios/land_circle_60s.yaml")};
  std::mt19937_64 rng(s.seed);
  std::vector<Outcome> outcomes;
  std::vector<std::string> names;
  for (const std::string& path : scenarios) {
    const Scenario sc = bench_scenario(path, s.cn0_dbhz);
    const NavData nav = read_rinex_nav(sc.nav_file);
    spdlog::info("{}: synthesizing {} points of {:.0f} s", sc.name, s.points, sc.duration_s);
    const std::vector<SnapshotPoint> points = scenario_points(sc, nav, s, rng);
    names.push_back(sc.name);
    for (Outcome& o : solve_points(sc.name, sc, nav, points, s)) outcomes.push_back(std::move(o));
  }
  BenchReport report("Snapshot positions (deepnav snap) against snapshot length",
                     {"scenario", "length_ms", "fixes", "snapshots", "median_h_m", "p95_h_m", "max_h_m", "cpu_ms"});
  for (const char* c : {"median_h_m", "p95_h_m", "max_h_m", "cpu_ms"}) report.set_precision(c, 1);
  names.push_back("all");
  for (const std::string& name : names)
    for (const int l : s.lengths_ms) add_row(report, name, l, outcomes);
  report.add_note("scenarios", scenarios.size());
  report.add_note("points_per_scenario", s.points);
  report.add_note("cn0_dbhz", s.cn0_dbhz);
  report.add_note("max_time_error_s", s.max_time_error_s);
  report.add_note("position_hint", s.position_hint ? nlohmann::json(s.max_hint_offset_m) : nlohmann::json(nullptr));
  report.add_note("seed", s.seed);
  report.emit(s.json_path);
  if (!s.plots_dir.empty()) {
    make_plots_dir(s.plots_dir);
    write_json_file((std::filesystem::path(s.plots_dir) / "snapshot_outcomes.json").string(),
                    {{"table", report.to_json()}, {"outcomes", outcomes_json(outcomes)}});
    if (run_plot_script("plot_snapshot.py", s.plots_dir)) spdlog::info("plot written to {}", s.plots_dir);
  }
}

}  // namespace deepnav::bench
