#pragma once
// One point of the jamming sweep: a scenario with one jammer at one J/S, synthesized with
// one seed and run through one receiver mode with one mitigation; the figures of that
// run against the truth, written as <out>/points/<id>/point.json (complete or absent).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "aiding/long_integrator.hpp"

#include "signals/sim/jammer.hpp"

namespace deepnav::bench {

struct JamPoint {
  std::string scenario;       ///< scenario file
  std::string jammer;         ///< cw, chirp, wideband, pulsed
  double js_db = 0.0;
  std::string mode = "scalar";
  std::string mitigation = "none";
  std::uint64_t seed = 1;
  double onset_s = 16.0;      ///< jammer on from here to the end of the scenario
  /// Ultra-tight long integration; a coherent length other than the default shows in the id.
  aiding::LongIntegrationConfig long_integration;
};

/// The benchmark's jammer of each type at this J/S (see README, "Jamming benchmark"):
/// CW 151.7 kHz off L1; chirp sweeping 2 MHz every 1 ms; wideband noise over 2.046 MHz;
/// pulsed noise bursts over 2.046 MHz, 10 % duty at 3 kHz.
JammerConfig benchmark_jammer(const std::string& type, double js_db, double onset_s);
/// "<scenario stem>_<jammer>_js<J/S>_<mode>_<mitigation>_s<seed>", a folder name.
std::string point_id(const JamPoint& p);
/// Folder of a point's results inside the sweep folder.
std::string point_dir(const std::string& out_dir, const JamPoint& p);
/// True when the point's point.json exists (the point finished before).
bool point_done(const std::string& out_dir, const JamPoint& p);

/// Thresholds that make a point a failure: the solution leaves 10 m (horizontal or
/// vertical, any solution, an aided mode's INS coast included), GNSS fixes (not in INS
/// coast, at least four satellites tracked) are missing for more than 5 % of the jammed
/// epochs, or the channels are tracked for less than half of the jammed time on average.
struct FailureCriteria {
  double max_error_m = 10.0;
  double min_fix_availability = 0.95;
  double min_tracked_fraction = 0.5;
};

/// Synthesizes, runs the receiver in-process (NavigationSession, every mode with the
/// broadcast ephemerides of the scenario's navigation file as assistance, so the first fix
/// comes at about 11 s) and writes point.json (its `command` is the equivalent `deepnav
/// run`); the IF file is deleted. Returns the figures.
nlohmann::json run_jam_point(const JamPoint& p, const std::string& out_dir);

}  // namespace deepnav::bench
