#pragma once
// `deepnav bench rx`: how fast the receiver runs. A 12-satellite scenario (4.092 Msps
// ibyte) is synthesized once; the receiver then processes it with 8 and 12 channels, on
// one thread and on every core, and in ultra-tight mode (12 channels, 100 Hz filter). The
// real-time factor is signal seconds per wall second. The correlator alone is timed on
// 12 channels' 1 ms spans for every kernel this CPU has. The report names the CPU, the
// instruction sets found and the kernel the receiver used (the settings' kernel or the
// environment variable DEEPNAV_CORRELATOR_KERNEL picks another, e.g. avx2 to measure as on
// a CPU without AVX-512). With Galileo among the systems (--systems gps,galileo), a mixed
// GPS+Galileo scenario (4 Msps) is synthesized too and the receiver processes it with GPS
// alone and with GPS+Galileo (12 GPS and 8 Galileo channels): the cost of the E1 channels
// and their acquisition on the same samples.
#include <string>
#include <vector>

#include "signals/satellite_id.hpp"

namespace deepnav::bench {

std::string default_rx_speed_scenario();
std::string default_rx_speed_galileo_scenario();

struct RxSpeedSettings {
  std::string scenario = default_rx_speed_scenario();  ///< 12 satellites and an imu section
  double duration_s = 60.0;                            ///< signal length
  int repeats = 3;                                     ///< runs per receiver case; the median is reported
  std::string work_dir;                              ///< where the (deleted) IF file goes; empty: the temporary folder
  std::string json_path;                             ///< the figures as JSON; empty: none
  std::string kernel;                                ///< correlator kernel for the receiver runs; empty: the default
  std::vector<GnssSystem> systems{GnssSystem::gps};  ///< with Galileo: the mixed-scenario rows too
  std::string galileo_scenario = default_rx_speed_galileo_scenario();  ///< GPS and Galileo satellites
};

/// Runs every case and prints the table (and writes the JSON asked for); throws InputError
/// for an unknown kernel or a scenario without an IMU.
void run_rx_speed_bench(const RxSpeedSettings& settings);

}  // namespace deepnav::bench
