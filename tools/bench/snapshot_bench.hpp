#pragma once
// `deepnav bench snapshot`: the accuracy of `deepnav snap` against snapshot length. Each
// scenario (by default the static and the land-circle ones, every satellite at 45 dB-Hz)
// is synthesized once, in memory, and snapshots are cut at `points` times spread over it;
// each point gets, from a seeded generator, a time hint off by 0 to max_time_error_s
// (either sign) and, unless position hints are off, a position hint 0 to
// max_hint_offset_m from the truth in a random direction. Every point is solved at every
// length; the horizontal errors against the trajectory give the median and the 95th
// percentile per length (per scenario and over all of them), with the fixes refused and
// the median CPU time of a solve.
#include <cstdint>
#include <string>
#include <vector>

namespace deepnav::bench {

struct SnapshotBenchSettings {
  std::vector<std::string> scenarios;  ///< empty: static_120s and land_circle_60s of data/scenarios
  int points = 20;
  std::vector<int> lengths_ms = {2, 5, 10, 20, 50, 100};
  double max_time_error_s = 60.0;
  bool position_hint = true;
  double max_hint_offset_m = 20e3;
  double cn0_dbhz = 45.0;
  std::uint64_t seed = 1;
  std::string json_path;  ///< the figures as JSON; empty: none
  std::string plots_dir;  ///< the per-snapshot errors and the PNG plot; empty: none
};

/// Prints the table (and writes the JSON and the plot asked for).
void run_snapshot_bench(const SnapshotBenchSettings& settings);

}  // namespace deepnav::bench
