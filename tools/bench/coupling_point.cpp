#include "tools/bench/coupling_point.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>

#include "ins/input_error.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/error_presets.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/bench/bench_report.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;

/// Settings a point records only when set, so that points made before they existed still
/// match: absent means false.
constexpr const char* kFlagsRecordedWhenSet[] = {"filter_troposphere", "filter_ionosphere"};

bool aircraft(const std::string& trajectory) { return trajectory.rfind("air", 0) == 0; }

std::uint64_t point_seed(const CouplingPoint& p) {
  return p.settings.seed + 1000 * static_cast<std::uint64_t>(p.run) + coupling_seed_index(p.trajectory);
}

/// The base scenario made into the point's: its trajectory, length, IMU grade, seed and
/// error world.
Scenario point_scenario(const CouplingPoint& p) {
  const CouplingPointSettings& o = p.settings;
  Scenario sc = load_scenario(o.base_scenario, DEEPNAV_SOURCE_DIR);
  sc.name = "coupling_" + coupling_point_name(p) + "_" + o.errors;
  sc.trajectory.preset = p.trajectory;
  if (aircraft(p.trajectory)) sc.trajectory.start.height_m = 1000.0;
  sc.duration_s = o.duration_s;
  sc.imu.enabled = true;
  sc.imu.grade = o.imu_grade;
  sc.seed = point_seed(p);
  sc.errors = error_preset(o.errors);
  validate_scenario(sc);
  require_scenario_systems(sc, o.systems, source_relative(o.base_scenario));
  return sc;
}

nlohmann::json mode_record(const AidedRunResult& r) {
  nlohmann::json epochs = nlohmann::json::array();
  for (const auto& e : r.epochs)
    epochs.push_back({e.t_s, aiding::to_string(e.mode), e.valid, e.error_ned_m(0), e.error_ned_m(1), e.error_ned_m(2),
                      e.velocity_error_mps});
  nlohmann::json m = {{"epochs", epochs}, {"wall_s", r.wall_s}, {"satellite_exclusions", r.satellite_exclusions}};
  // Whether (and when) a model mismatch was found: what changed the filter's states.
  const auto when = [](const std::optional<double>& t) { return t ? nlohmann::json(*t) : nlohmann::json(nullptr); };
  m["troposphere_mismatch_s"] = when(r.troposphere_mismatch_s);
  m["ionosphere_mismatch_s"] = when(r.ionosphere_mismatch_s);
  return m;
}

}  // namespace

const std::vector<std::string>& coupling_trajectories() {
  static const std::vector<std::string> t{"land-straight", "land-accel", "land-circle",   "land-s",
                                          "air-circle",    "air-s",      "air-spiral",    "air-wingrock",
                                          "air-circle-x2", "air-s-x2",   "air-spiral-x2", "air-wingrock-x2"};
  return t;
}

std::size_t coupling_seed_index(const std::string& trajectory) {
  const auto& all = coupling_trajectories();
  const auto it = std::find(all.begin(), all.end(), trajectory);
  if (it == all.end()) throw InputError("--trajectories: unknown trajectory '" + trajectory + "'");
  return static_cast<std::size_t>(it - all.begin());
}

std::string default_coupling_scenario() { return source_tree_path("data/scenarios/land_circle_aided_90s.yaml"); }

std::string coupling_point_name(const CouplingPoint& p) { return fmt::format("{}_r{:03d}", p.trajectory, p.run); }

nlohmann::json coupling_point_settings(const CouplingPoint& p) {
  const CouplingPointSettings& o = p.settings;
  nlohmann::json s = {{"trajectory", p.trajectory},
                      {"run", p.run},
                      {"seed", point_seed(p)},
                      {"errors", o.errors},
                      {"duration_s", o.duration_s},
                      {"imu_grade", o.imu_grade},
                      {"scenario", source_relative(o.base_scenario)},
                      {"receiver_ionosphere", to_string(o.atmosphere.ionosphere)},
                      {"receiver_troposphere", to_string(o.atmosphere.troposphere)}};
  if (o.filter_troposphere) s[kFlagsRecordedWhenSet[0]] = true;
  if (o.filter_ionosphere) s[kFlagsRecordedWhenSet[1]] = true;
  // Recorded only beside GPS, so that the GPS-only points made before keep their settings.
  if (!is_gps_only(o.systems)) s["systems"] = systems_list(o.systems);
  return s;
}

std::vector<std::string> coupling_point_command(const std::string& exe, const CouplingPoint& p,
                                                const std::string& out_dir) {
  const CouplingPointSettings& o = p.settings;
  std::string modes;
  for (const auto& m : o.modes) modes += (modes.empty() ? "" : ",") + m;
  std::vector<std::string> cmd{exe,
                               "bench",
                               "coupling",
                               "--trajectories",
                               p.trajectory,
                               "--first-run",
                               std::to_string(p.run),
                               "--runs",
                               "1",
                               "--modes",
                               modes,
                               "--errors",
                               o.errors,
                               "--duration",
                               fmt::format("{}", o.duration_s),
                               "--imu-grade",
                               o.imu_grade,
                               "--scenario",
                               o.base_scenario,
                               "--seed",
                               std::to_string(o.seed),
                               "--ionosphere",
                               to_string(o.atmosphere.ionosphere),
                               "--troposphere",
                               to_string(o.atmosphere.troposphere),
                               "--out",
                               out_dir};
  if (o.filter_troposphere) cmd.push_back("--filter-troposphere");
  if (o.filter_ionosphere) cmd.push_back("--filter-ionosphere");
  if (!is_gps_only(o.systems)) {
    cmd.push_back("--systems");
    cmd.push_back(systems_list(o.systems));
  }
  return cmd;
}

nlohmann::json run_coupling_point(const CouplingPoint& p, const std::string& work_dir) {
  const CouplingPointSettings& o = p.settings;
  const Scenario sc = point_scenario(p);
  const std::string dir = (fs::path(work_dir) / sc.name).string();
  SynthesisOptions so;
  so.threads = 1;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir, so);
  // Aircraft turns ramp the Doppler by tens of Hz/s: third-order PLL for them.
  AidedRunSettings run_settings;
  run_settings.pll_order = aircraft(p.trajectory) ? 3 : 2;
  run_settings.atmosphere = o.atmosphere;
  run_settings.filter_troposphere = o.filter_troposphere;
  run_settings.filter_ionosphere = o.filter_ionosphere;
  run_settings.systems = o.systems;
  nlohmann::json point = coupling_point_settings(p);
  for (const auto& m : o.modes)
    point["modes"][m] = mode_record(run_aided_scenario(sc, s, aiding::parse_nav_mode(m), run_settings));
  fs::remove_all(dir);
  return point;
}

std::string coupling_point_path(const std::string& out_dir, const CouplingPoint& p) {
  return (fs::path(out_dir) / "points" / (coupling_point_name(p) + ".json")).string();
}

void write_coupling_point(const std::string& out_dir, const CouplingPoint& p, const nlohmann::json& point) {
  const fs::path path = coupling_point_path(out_dir, p);
  fs::create_directories(path.parent_path());
  TextOutputFile f(path.string());
  f.write(point.dump(1) + "\n");
  f.commit();
}

nlohmann::json load_coupling_point(const std::string& out_dir, const CouplingPoint& p) {
  const fs::path path = coupling_point_path(out_dir, p);
  if (!fs::exists(path)) return nullptr;
  std::ifstream in(path);
  nlohmann::json point;
  try {
    point = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("{}: not a coupling point ({}); delete it to run the point again", path.string(), e.what()));
  }
  const nlohmann::json want = coupling_point_settings(p);
  for (const auto& [key, value] : want.items())
    if (!point.contains(key) || point[key] != value)
      throw InputError(fmt::format("{}: made with {} = {}, this run asks for {}; use another --out", path.string(), key,
                                   point.contains(key) ? point[key].dump() : "nothing", value.dump()));
  // A flag the point was made with and this run does not ask for is another setting too.
  if (point.value("systems", "gps") != want.value("systems", "gps"))
    throw InputError(fmt::format("{}: made with systems {}, this run asks for {}; use another --out", path.string(),
                                 point.value("systems", "gps"), want.value("systems", "gps")));
  for (const char* flag : kFlagsRecordedWhenSet)
    if (point.value(flag, false) != want.value(flag, false))
      throw InputError(fmt::format("{}: made with {} = {}, this run asks for {}; use another --out", path.string(),
                                   flag, point.value(flag, false), want.value(flag, false)));
  for (const auto& m : p.settings.modes)
    if (!point["modes"].contains(m))
      throw InputError(fmt::format("{}: has no '{}' run; use another --out or the point's modes", path.string(), m));
  return point;
}

}  // namespace deepnav::bench
