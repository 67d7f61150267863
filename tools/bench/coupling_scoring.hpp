#pragma once
// The coupling benchmark's scoring of its runs: each run's RMS error over the scored span
// and its error at the time the paper quotes, the spread of a figure over runs, and whether
// one mode beats another in the runs' paired differences.
#include <Eigen/Core>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace deepnav::bench {

/// One mode of one run, scored.
struct RunScore {
  double rms_h_m = NAN, rms_3d_m = NAN;       ///< NaN: no valid epoch in the scored span
  std::optional<Eigen::Vector3d> error_at_m;  ///< north/east/down at the scoring time
  double in_mode_s = 0.0, scored_s = 0.0;     ///< epochs in the requested mode, epochs scored
};

/// Scores a mode's epochs as a coupling point records them ([t_s, mode, valid, n, e, d,
/// velocity error]) from `score_from_s` on, with the error vector taken at `score_at_s`.
RunScore score_run(const nlohmann::json& epochs, const std::string& mode, double score_from_s, double score_at_s);

/// The vertical RMS of a mode's epochs from `from_s` on (NaN: no valid epoch there): how
/// well the height has settled after a delay model's mismatch was found.
double vertical_rms_from(const nlohmann::json& epochs, double from_s);

/// When a mode's run first found a delay model mismatch (troposphere or ionosphere, as the
/// point records them); nullopt when it found none.
std::optional<double> mismatch_found_s(const nlohmann::json& mode_record);

struct Spread {
  double mean = NAN, std = NAN;  ///< std: sample standard deviation (0 for one value)
  int n = 0;
};
Spread spread(const std::vector<double>& values);

/// Whether `better` beats `worse` in the runs' paired differences: "yes" when the mean
/// difference is below zero by more than two standard errors, "no" when above by as
/// much, "tie" in between ("yes(1 run)"/"no(1 run)" for one pair, "n/a" for none).
std::string paired_verdict(const std::vector<double>& better, const std::vector<double>& worse);

}  // namespace deepnav::bench
