#pragma once
// One point of the coupling benchmark (paper 003 [docs/references.md]): one trajectory, synthesized with an IMU
// of the paper's figures in a chosen error world with one run's seed, then run through the
// receiver in each mode asked for; the errors are the solutions' own against the
// synthesizer's truth. A point is kept as <out>/points/<trajectory>_r<run>.json, so a sweep
// resumes where it stopped, and is one command (coupling_point_command) for running apart.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "receiver/pvt/atmosphere_models.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav::bench {

/// The trajectory presets: the four land and four aircraft paths, and the aircraft set with
/// doubled rates and angles. Their order fixes their seeds.
const std::vector<std::string>& coupling_trajectories();
/// A trajectory's place in that list: its scenarios' seeds do not depend on which other
/// trajectories a sweep names, so a subset reproduces the full table's rows. Throws
/// InputError for an unknown trajectory.
std::size_t coupling_seed_index(const std::string& trajectory);
/// The base scenario (signal, clock, IMU lever arm) unless told otherwise.
std::string default_coupling_scenario();

/// What every point of a sweep is made with, besides its trajectory and run.
struct CouplingPointSettings {
  std::vector<std::string> modes{"loose", "tight", "ultra"};
  std::string errors = "none";  ///< error world preset
  double duration_s = 200.0;
  std::string imu_grade = "paper003";
  std::string base_scenario = default_coupling_scenario();
  std::uint64_t seed = 300;         ///< base seed: a point's is seed + 1000 run + trajectory index
  AtmosphereModels atmosphere;      ///< the receiver's (the scenario decides what is synthesized)
  bool filter_troposphere = false;  ///< tight/ultra: the zenith troposphere residual state
  bool filter_ionosphere = false;   ///< tight/ultra: the ionosphere model's scale state
  /// The systems the receiver tracks; with Galileo the base scenario must carry Galileo
  /// satellites (data/scenarios/land_circle_gps_galileo_aided.yaml).
  std::vector<GnssSystem> systems{GnssSystem::gps};
};

struct CouplingPoint {
  std::string trajectory;
  int run = 0;
  CouplingPointSettings settings;
};

/// "<trajectory>_r<run, 3 digits>".
std::string coupling_point_name(const CouplingPoint& p);
/// What the point's figures depend on (its seed included): a finished point made with
/// other settings must not be mixed into a table. Recorded in the point's file.
nlohmann::json coupling_point_settings(const CouplingPoint& p);
/// The command that makes this point alone into `out_dir`: `<exe> bench coupling ...` with
/// every setting of `p` as the coupling options read it.
std::vector<std::string> coupling_point_command(const std::string& exe, const CouplingPoint& p,
                                                const std::string& out_dir);

/// Synthesizes the point's scenario into `work_dir` (removed afterwards) and runs every
/// mode: the point's settings with, per mode, each epoch's error, the wall time, the
/// satellite exclusions and when a model mismatch was found.
nlohmann::json run_coupling_point(const CouplingPoint& p, const std::string& work_dir);

/// <out>/points/<name>.json
std::string coupling_point_path(const std::string& out_dir, const CouplingPoint& p);
void write_coupling_point(const std::string& out_dir, const CouplingPoint& p, const nlohmann::json& point);
/// The finished point, or null; throws InputError when it was made with other settings or
/// lacks a mode asked for.
nlohmann::json load_coupling_point(const std::string& out_dir, const CouplingPoint& p);

}  // namespace deepnav::bench
