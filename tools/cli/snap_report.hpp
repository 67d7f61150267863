#pragma once
// What `deepnav snap` reports of each snapshot: the JSON document (--json) and the table
// it prints.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "receiver/snapshot_positioner.hpp"

namespace deepnav::cli {

struct SnapEntry {
  double t_s = 0.0;  ///< snapshot start, seconds after the file's first sample
  GpsTime t_hint{};  ///< the time hint of its first sample
  int length_ms = 0;
  double solve_cpu_ms = 0.0;  ///< CPU time of acquisition, refinement and fix (one thread)
  SnapshotResult result;
};

/// "good": a fix whose residual test had 2 or more degrees of freedom; "marginal": one
/// (a wrong satellite could not be told from the rest); "none": no fix.
std::string quality_flag(const CoarseTimeFix& fix);

/// {"t_s", "lat_deg", "lon_deg", "height_m", "time_correction_s", "satellites", ...}:
/// coordinates and time null, and "reason" set, for a snapshot that could not be solved.
nlohmann::json snapshot_json(const SnapEntry& entry);

/// The whole document: the input, the hints and "snapshots".
nlohmann::json snap_document(const std::string& input, const std::string& nav, const std::vector<SnapEntry>& entries);

/// One line per snapshot (time, position or reason, satellites, correction, quality).
std::string snap_table(const std::vector<SnapEntry>& entries);

/// The satellites a snapshot holds, one line each (what is printed before a failure).
std::string signals_table(const SnapshotResult& result);

}  // namespace deepnav::cli
