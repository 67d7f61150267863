#pragma once
// The jamming sweep's report from every finished point in a sweep folder: runs.csv (one
// row per point), thresholds.md (first failing J/S per scenario, jammer, mode and
// mitigation, and what the mitigation gains over none) and the same table for the
// terminal/JSON.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/bench/bench_report.hpp"

namespace deepnav::bench {

/// Every <out>/points/*/point.json, sorted by scenario, jammer, mode, mitigation, seed, J/S.
std::vector<nlohmann::json> load_jam_points(const std::string& out_dir);
/// Writes <out>/runs.csv and <out>/thresholds.md and returns the threshold table.
BenchReport write_jam_report(const std::vector<nlohmann::json>& points, const std::string& out_dir);

}  // namespace deepnav::bench
