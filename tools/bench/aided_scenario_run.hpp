#pragma once
// One synthesized scenario through the receiver in one mode, scored against the
// synthesizer's truth: what the aiding benchmarks (coupling, weak-signal threshold) repeat
// over trajectories, modes, C/N0 levels and seeds.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "aiding/aided_receiver.hpp"
#include "aiding/navigation_session.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"

namespace deepnav::bench {

struct EpochError {
  double t_s = 0.0;
  aiding::NavMode mode = aiding::NavMode::scalar;
  bool valid = false;
  Eigen::Vector3d error_ned_m = Eigen::Vector3d::Zero();  ///< solution minus truth (antenna)
  double velocity_error_mps = 0.0;
  /// Satellites whose measurements the solution used: the receiver PVT's in scalar and
  /// loose mode, observables in tight mode, discriminator measurements in ultra mode.
  int gnss_measurements = 0;
};

struct AidedRunResult {
  std::vector<EpochError> epochs;   ///< one per observation epoch
  std::map<int, double> tracked_s;  ///< per PRN: seconds of integrations with C/N0 above the loss threshold
  double first_aided_s = -1.0;      ///< first epoch in a coupled mode (-1: never)
  std::vector<aiding::ModeChange> mode_changes;
  double wall_s = 0.0;
  int satellite_exclusions = 0;  ///< satellites the aided filter's fault monitor excluded
  int filter_restarts = 0;
  /// When the aided filter found the troposphere or the ionosphere model not to match the
  /// signal (and took that state); nullopt: not found.
  std::optional<double> troposphere_mismatch_s, ionosphere_mismatch_s;
};

/// How to read the IF file the synthesizer wrote for `scenario`.
FileSampleSourceOptions synthesized_source(const Scenario& scenario, const SynthesisSummary& synthesis);

/// What a benchmark may change in the receiver and the aided filter for one run.
struct AidedRunSettings {
  /// 3 suits high dynamics (aircraft turns): it follows a Doppler ramp without a
  /// steady-state phase error.
  int pll_order = 2;
  /// The receiver's models (turn one off for a scenario synthesized without that delay).
  AtmosphereModels atmosphere;
  /// Tight and ultra-tight: the zenith troposphere residual state (an 18th state).
  bool filter_troposphere = false;
  /// Tight and ultra-tight: the ionosphere model's scale state (a 19th state).
  bool filter_ionosphere = false;
  /// Ultra-tight: long integration of weak channels (data wipe-off).
  aiding::LongIntegrationConfig long_integration;
  /// The systems the receiver tracks (the scenario must carry them; Galileo needs 4 Msps).
  std::vector<GnssSystem> systems{GnssSystem::gps};
};

/// The session for a synthesized scenario in `mode`: its week, its navigation file's
/// ionosphere and ephemerides as assistance, and in an aided mode its IMU's grade and lever arm.
aiding::NavigationSessionConfig scenario_session_config(const Scenario& scenario, aiding::NavMode mode);
/// The IMU log the synthesizer wrote, for an aided mode (nullopt in scalar mode).
std::optional<ImuLog> scenario_imu_log(const SynthesisSummary& synthesis, aiding::NavMode mode);

/// Runs `mode` (scalar included) on a synthesized scenario with assisted ephemerides and
/// ionosphere from the scenario's navigation file.
AidedRunResult run_aided_scenario(const Scenario& scenario, const SynthesisSummary& synthesis, aiding::NavMode mode,
                                  const AidedRunSettings& settings = {});

}  // namespace deepnav::bench
