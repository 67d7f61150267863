#pragma once
// A `deepnav run` of an IF file as one value: what a benchmark runs in-process and what it
// records as the command that reruns it by hand. Both come from this value (run_command,
// run_session_config), so the record cannot describe another run than the one made.
#include <optional>
#include <string>
#include <vector>

#include "aiding/long_integrator.hpp"
#include "aiding/navigation_session.hpp"
#include "ins/imu_file.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "signals/sample_format.hpp"
#include "tools/bench/receiver_modes.hpp"

namespace deepnav::bench {

struct RunConfiguration {
  // The IF file (--input, --format, --fs, --if).
  std::string input;
  SampleFormat format = SampleFormat::ibyte;
  double sample_rate_hz = 0.0;
  double if_hz = 0.0;
  int week = 0;                ///< --week; 0: not given
  std::string iono_from;       ///< --iono-from: RINEX navigation file; empty: none
  std::string ephemeris_from;  ///< --ephemeris-from: RINEX navigation file; empty: none
  std::string truth;           ///< --truth: the synthesizer's truth.csv; empty: none
  std::string mitigation = "none";
  // Ultra-tight long integration: what `deepnav run` lets one choose of it (the rest of
  // aiding::LongIntegrationConfig stays at its defaults).
  int coherent_ms = aiding::LongIntegrationConfig{}.coherent_ms;
  int noncoherent_ms = aiding::LongIntegrationConfig{}.noncoherent_ms;
  bool assist_data_bits = false;
  std::string mode = "scalar";                       ///< a row of receiver_modes()
  RunImu imu;                                        ///< the aided modes' IMU (--imu, --imu-grade, ...)
  std::string out_dir;                               ///< --out: where `deepnav run` writes its products
  std::vector<GnssSystem> systems{GnssSystem::gps};  ///< --systems
};

/// The `deepnav run` command line ("deepnav", "run", options...) of this configuration:
/// the IF file, the week, the assistance and truth files, the mitigation, the long
/// integration, the output folder and the mode's own arguments (receiver_modes). Throws
/// InputError for an unknown mode, or an aided mode without an IMU file.
std::vector<std::string> run_command(const RunConfiguration& run);

/// What `deepnav run` reads the IF file with, from those options.
FileSampleSourceOptions run_source_options(const RunConfiguration& run);
/// The session `deepnav run` builds from those options (the assistance files read here;
/// the IMU's grade in an aided mode). Throws InputError when a file cannot be read.
aiding::NavigationSessionConfig run_session_config(const RunConfiguration& run);
/// The IMU log of an aided mode (nullopt in scalar mode).
std::optional<ImuLog> run_imu_log(const RunConfiguration& run);

}  // namespace deepnav::bench
