#pragma once
// One point of the jamming sweep: a scenario with one jammer at one J/S, synthesized with
// one seed and run through one receiver mode with one mitigation; the figures of that
// run against the truth, written as <out>/points/<id>/point.json (complete or absent).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "aiding/long_integrator.hpp"
#include "signals/satellite_id.hpp"
#include "signals/sim/jammer.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/run_configuration.hpp"

namespace deepnav::bench {

struct JamPoint {
  std::string scenario;  ///< scenario file
  std::string jammer;    ///< cw, chirp, wideband, pulsed
  double js_db = 0.0;
  std::string mode = "scalar";
  std::string mitigation = "none";
  std::uint64_t seed = 1;
  double onset_s = 16.0;  ///< jammer on from here to the end of the scenario
  /// Ultra-tight long integration; a coherent length other than the default shows in the id.
  aiding::LongIntegrationConfig long_integration;
  /// The systems the receiver tracks (the scenario must carry them); other than GPS alone
  /// they show in the id.
  std::vector<GnssSystem> systems{GnssSystem::gps};
};

/// The benchmark's jammer of each type at this J/S (see docs/jamming.md, "The sweep"):
/// CW 151.7 kHz off L1; chirp sweeping 2 MHz every 1 ms; wideband noise over 2.046 MHz;
/// pulsed noise bursts over 2.046 MHz, 10 % duty at 3 kHz.
JammerConfig benchmark_jammer(const std::string& type, double js_db, double onset_s);
/// "<scenario stem>_<jammer>_js<J/S>_<mode>_<mitigation>_s<seed>", a folder name (with
/// "_gps-galileo" at the end for both systems).
std::string point_id(const JamPoint& p);
/// Folder of a point's results inside the sweep folder.
std::string point_dir(const std::string& out_dir, const JamPoint& p);
/// True when the point's point.json exists (the point finished before).
bool point_done(const std::string& out_dir, const JamPoint& p);

/// The point's scenario: its seed, and the benchmark jammer from the onset to the end.
/// Throws InputError for an onset outside the scenario, an aided mode on a scenario without
/// an IMU, or a scenario that does not load.
Scenario jam_point_scenario(const JamPoint& p);

/// Where the synthesizer wrote the point's signal and truth.
struct JamPointFiles {
  std::string if_path, truth_path, imu_path;
  std::string run_dir;  ///< where a rerun by hand writes its products
};

/// The `deepnav run` of the point: its IF file, week, the broadcast ephemerides and
/// ionosphere of the scenario's navigation file as assistance (every mode, so the first fix
/// comes at about 11 s), its mitigation, long integration, mode and the scenario's IMU.
RunConfiguration jam_point_run(const JamPoint& p, const Scenario& scenario, const JamPointFiles& files);

/// Synthesizes, runs jam_point_run in-process and writes point.json (its `command` is that
/// run's `deepnav run`); the IF file is deleted. Returns the figures.
nlohmann::json run_jam_point(const JamPoint& p, const std::string& out_dir);

/// One line for the terminal: the point's id, its main figures and its verdict.
std::string jam_point_summary(const nlohmann::json& figures);

}  // namespace deepnav::bench
