#pragma once
// `deepnav bench stream`: loopback throughput server -> receiver (MB/s, real-time factor,
// channels tracking) as fast as the receiver reads, and the CPU the receiver needs when the
// server paces the stream at real time, with the samples lost.
#include <string>

namespace deepnav::bench {

struct StreamBenchSettings {
  /// Made to have every satellite above the horizon, up to 12; a relative path is looked up
  /// in the source tree too, so the default works from anywhere.
  std::string scenario_path = "data/scenarios/rx_speed_12sat.yaml";
  double duration_s = 30.0;  ///< seconds of signal for the as-fast-as-possible run
  double paced_s = 10.0;     ///< seconds of signal for the real-time run
  std::string json_path;     ///< the figures as JSON; empty: none
};

/// Synthesizes the scenario, runs both cases and prints the table (and writes the JSON
/// asked for); throws InputError for bad lengths or a scenario that does not load.
void run_stream_bench(const StreamBenchSettings& settings);

}  // namespace deepnav::bench
