#pragma once
// `deepnav bench threshold`: the lowest C/N0 at which the tracking loops keep lock. A
// scenario whose C/N0 falls slowly (a linear ramp) is synthesized and run. Scalar (the
// default): for each channel, the last moment its carrier frequency still follows the true
// Doppler (within 5 Hz, from the synthesizer's per-satellite truth) and its first cycle
// slip are read off the ramp. Per mode (on an aided scenario): the C/N0 at which each mode
// first stops holding a 10 m solution from satellite measurements.
#include <string>
#include <vector>

#include "aiding/long_integrator.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav::bench {

/// The static scenario of the scalar sweep and the aided one of the per-mode sweep.
std::string default_threshold_scenario();
std::string default_threshold_aided_scenario();

struct ThresholdBenchSettings {
  std::string scenario = default_threshold_scenario();  ///< base scenario of the scalar sweep (static)
  double start_dbhz = 40.0;                             ///< C/N0 before the ramp
  double ramp_start_s = 15.0;
  double rate_dbps = 0.25;         ///< C/N0 fall rate
  double end_dbhz = 15.0;          ///< lowest C/N0
  std::string json_path;           ///< the figures as JSON; empty: none
  std::string work_dir;            ///< where the (deleted) IF file goes; empty: the temporary folder
  std::vector<std::string> modes;  ///< non-empty: the per-mode threshold on the aided scenario
  std::string aided_scenario = default_threshold_aided_scenario();  ///< of the per-mode sweep (needs an imu section)
  std::string imu_grade;   ///< per mode: this grade instead of the scenario's (empty: the scenario's)
  std::string oscillator;  ///< per mode: this oscillator instead of the scenario's (empty: the scenario's)
  aiding::LongIntegrationConfig long_integration;  ///< ultra-tight long integration
  std::string long_integration_text;               ///< how the report describes long_integration
  /// Per mode: the systems the receiver tracks (the aided scenario must carry them).
  std::vector<GnssSystem> systems{GnssSystem::gps};
};

/// The ramp's C/N0 at time t (dB-Hz).
double ramp_cn0_dbhz(const ThresholdBenchSettings& settings, double t_s);

/// The scalar sweep, or the per-mode one when modes are named; prints the table (and
/// writes the JSON asked for).
void run_threshold_bench(const ThresholdBenchSettings& settings);

}  // namespace deepnav::bench
