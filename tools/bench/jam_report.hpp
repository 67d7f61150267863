#pragma once
// The jamming sweep's report from every finished point in a sweep folder: runs.csv (one
// row per point), thresholds.md (first failing J/S per scenario, jammer, mode and
// mitigation, and what the mitigation gains over none) and the same table for the
// terminal/JSON.
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/bench/bench_report.hpp"

namespace deepnav::bench {

/// A threshold of a series that never crossed it: every J/S tested passed.
inline constexpr double kNoJamFailure = std::numeric_limits<double>::infinity();

/// The thresholds of one series of points: one scenario, jammer, mode and mitigation, over
/// the J/S values and seeds its points ran.
struct JamThreshold {
  std::string scenario, jammer, mode, mitigation;
  double js_min_db = 0.0, js_max_db = 0.0;  ///< J/S tested
  /// Per seed (in seed order): the first J/S at which the point failed; kNoJamFailure when
  /// every J/S passed.
  std::vector<double> first_failure_db;
  double median_first_failure_db = kNoJamFailure;  ///< the median of those
  std::string failure;                             ///< why the points at those thresholds failed, each reason once
  /// What the mitigation gains over none on the seeds both series ran: "12.5"; "> 8.0" when
  /// the mitigation never failed; "n/a (...)" when it cannot be said; "" for none itself
  /// or without a series without mitigation.
  std::string gain_over_none;
  /// The median over seeds of the first J/S at which the satellites see their signal less
  /// than half of the time (signal_fraction_mean); kNoJamFailure when never.
  double median_signal_lost_db = kNoJamFailure;
};

/// Every <out>/points/*/point.json, sorted by scenario, jammer, mode, mitigation, seed, J/S.
std::vector<nlohmann::json> load_jam_points(const std::string& out_dir);
/// The thresholds of every series in `points` (as load_jam_points sorts them), in the order
/// scenario, jammer, mode, mitigation.
std::vector<JamThreshold> jam_thresholds(const std::vector<nlohmann::json>& points);
/// A threshold as the report writes it: "35.0", or "> 60.0" (nothing failed up to js_max_db).
std::string threshold_text(double threshold_db, double js_max_db);
/// Writes <out>/runs.csv and <out>/thresholds.md and returns the threshold table.
BenchReport write_jam_report(const std::vector<nlohmann::json>& points, const std::string& out_dir);

}  // namespace deepnav::bench
