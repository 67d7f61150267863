#pragma once
// `deepnav bench sim`: synthesis speed (seconds of signal per second of wall time) on one
// core and on all cores, and the peak resident memory of the process.
#include <string>
#include <vector>

#include "signals/satellite_id.hpp"

namespace deepnav::bench {

std::string default_sim_speed_scenario();

struct SimSpeedSettings {
  std::string scenario = default_sim_speed_scenario();  ///< base scenario (its time, place and clock are used)
  double duration_s = 10.0;                             ///< seconds of signal per run
  int satellites = 10;                                  ///< of each system
  std::vector<GnssSystem> systems;                      ///< empty: the scenario's
  std::string format = "ibyte";
  int adc_bits = 2;
  std::string work_dir;   ///< where the (deleted) IF files go; empty: the temporary folder
  std::string json_path;  ///< the figures as JSON; empty: none
};

/// Synthesizes on one thread and on every core and prints the table (and writes the JSON
/// asked for).
void run_sim_speed_bench(const SimSpeedSettings& settings);

}  // namespace deepnav::bench
