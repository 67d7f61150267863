#pragma once
// The coupling benchmark's report over its points: per trajectory and mode the error at the
// scoring time beside paper 003's figures, the runs' RMS errors (mean and spread) and the
// share of epochs in the requested mode; the ordering ultra <= tight <= loose, paired over
// runs; and in how many runs a model mismatch was found. Also the per-epoch CSV.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tools/bench/bench_report.hpp"
#include "tools/bench/coupling_sweep.hpp"

namespace deepnav::bench {

/// `points`: every point of the sweep (coupling_sweep_points' order); `kept_in`: the folder
/// that keeps them, for the report's notes.
BenchReport coupling_report(const CouplingSweepSettings& settings, const std::vector<nlohmann::json>& points,
                            const std::optional<std::string>& kept_in);

/// Per mode, in how many points the aided filter found the troposphere or the ionosphere
/// model not to match the signal ("-": points written before that was recorded).
nlohmann::json mismatch_counts(const std::vector<nlohmann::json>& points, const std::vector<std::string>& modes);

/// Every epoch of every run: trajectory, run, requested mode, time, mode, validity, error.
void write_coupling_csv(const std::string& path, const std::vector<nlohmann::json>& points);

}  // namespace deepnav::bench
