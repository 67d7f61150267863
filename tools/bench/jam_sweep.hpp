#pragma once
// The jamming sweep (`deepnav bench jam`): J/S sweeps of one scenario under CW, chirp,
// wideband and pulsed jammers, for every receiver mode and mitigation asked for. Each point
// (scenario, jammer, J/S, mode, mitigation, seed) is one deterministic command, `deepnav
// bench jam-point ...`; the sweep runs the unfinished ones in parallel, skips those already
// in the sweep folder (resume), prints them instead when asked (GNU parallel, a Slurm
// array), and then reports over every finished point in the folder: runs.csv,
// thresholds.md and PNG plots.
#include <string>
#include <vector>

#include "aiding/long_integrator.hpp"
#include "tools/bench/jam_point.hpp"

namespace deepnav::bench {

/// The scenario the sweep jams unless told otherwise.
std::string default_jam_scenario();

struct JamSweepSettings {
  std::string scenario = default_jam_scenario();  ///< base scenario (the jammer is added from onset_s)
  std::string jammers = "cw";                     ///< comma-separated jammer types
  std::string js = "20:60:5";                     ///< FROM:TO:STEP (dB), or one value
  std::string modes = "scalar";                   ///< comma-separated receiver modes
  std::string mitigations = "none,auto";
  int runs = 1;  ///< seeds per point: the scenario's, +1, ...
  double onset_s = 16.0;
  std::string out_dir;         ///< sweep folder
  int jobs = 1;                ///< points run at the same time
  bool list_commands = false;  ///< print the unfinished points' commands instead
  bool no_plots = false;
  std::string json_path;  ///< the threshold table as JSON; empty: none
  aiding::LongIntegrationConfig long_integration;
  std::vector<GnssSystem> systems{GnssSystem::gps};  ///< what the receiver tracks
};

/// FROM:TO:STEP (or one value) in dB, each rounded to 0.1 dB; throws InputError naming --js.
std::vector<double> parse_js_range(const std::string& text);
/// Every point of the sweep, in the order they run; throws InputError for a setting that
/// names an unknown jammer, mode or mitigation, an aided mode on a scenario without an
/// IMU, or an onset outside the scenario.
std::vector<JamPoint> jam_sweep_points(const JamSweepSettings& settings);
/// The command that runs one point alone: `<exe> -q bench jam-point ...`, every field of
/// `point` as the jam-point options read it.
std::vector<std::string> jam_point_command(const std::string& exe, const JamPoint& point, const std::string& out_dir);

/// Lists, or runs and reports, the sweep (see above); throws InputError when points fail.
void run_jam_sweep(const JamSweepSettings& settings);

}  // namespace deepnav::bench
