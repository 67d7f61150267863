#include "tools/bench/coupling_report.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <cmath>
#include <map>

#include "ins/input_error.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/coupling_scoring.hpp"

namespace deepnav::bench {
namespace {

/// The height is scored this long after a delay model's mismatch was found (the filter
/// takes the model's state on it and needs a few seconds to settle).
constexpr double kSettleAfterMismatchS = 10.0;

/// Paper 003's 1-sigma position errors at 150 s (m, x/y/z), where the paper states them.
const std::map<std::pair<std::string, std::string>, Eigen::Vector3d>& paper_figures() {
  static const std::map<std::pair<std::string, std::string>, Eigen::Vector3d> f{
      {{"land-circle", "tight"}, {2.384, 3.251, 1.455}}, {{"land-circle", "ultra"}, {0.430, 1.015, 0.906}},
      {{"air-circle", "loose"}, {1.783, 2.429, 5.512}},  {{"air-circle", "tight"}, {1.248, 1.177, 3.881}},
      {{"air-circle", "ultra"}, {0.591, 0.634, 0.896}},
  };
  return f;
}

/// One trajectory's rows; returns its ordering verdicts (null unless loose, tight and
/// ultra all ran).
nlohmann::json add_trajectory_rows(BenchReport& report, const CouplingSweepSettings& o, const std::string& traj,
                                   const std::vector<nlohmann::json>& points) {
  std::map<std::string, std::vector<double>> per_run_h, per_run_3d, per_run_v_settled;
  std::map<std::string, double> mean_h, mean_3d;
  for (const auto& mode : o.point.modes) {
    Eigen::Vector3d sum2_at = Eigen::Vector3d::Zero();
    int n_at = 0;
    double in_mode = 0.0, scored = 0.0;
    for (const auto& p : points) {
      if (p["trajectory"] != traj) continue;
      const RunScore s = score_run(p["modes"][mode]["epochs"], mode, o.score_from_s, o.score_at_s);
      per_run_h[mode].push_back(s.rms_h_m);
      per_run_3d[mode].push_back(s.rms_3d_m);
      if (const auto found = mismatch_found_s(p["modes"][mode]))
        per_run_v_settled[mode].push_back(
            vertical_rms_from(p["modes"][mode]["epochs"], *found + kSettleAfterMismatchS));
      if (s.error_at_m) {
        sum2_at += s.error_at_m->cwiseAbs2();
        ++n_at;
      }
      in_mode += s.in_mode_s;
      scored += s.scored_s;
    }
    const Eigen::Vector3d at = n_at ? Eigen::Vector3d((sum2_at / n_at).cwiseSqrt()) : Eigen::Vector3d::Constant(NAN);
    const Spread h = spread(per_run_h[mode]), d3 = spread(per_run_3d[mode]);
    mean_h[mode] = h.mean;
    mean_3d[mode] = d3.mean;
    const auto paper = paper_figures().find({traj, mode});
    const Eigen::Vector3d pf = paper == paper_figures().end() ? Eigen::Vector3d::Constant(NAN) : paper->second;
    report.add_row({traj, mode, at(0), at(1), at(2), pf(0), pf(1), pf(2), h.mean, h.std, d3.mean, d3.std,
                    spread(per_run_v_settled[mode]).mean, scored > 0 ? 100.0 * in_mode / scored : 0.0});
  }
  if (!(mean_h.count("loose") && mean_h.count("tight") && mean_h.count("ultra"))) return nullptr;
  const bool h_ok = mean_h["ultra"] <= mean_h["tight"] && mean_h["tight"] <= mean_h["loose"];
  const bool d3_ok = mean_3d["ultra"] <= mean_3d["tight"] && mean_3d["tight"] <= mean_3d["loose"];
  std::vector<double> ultra_minus_tight;
  for (std::size_t i = 0; i < std::min(per_run_h["ultra"].size(), per_run_h["tight"].size()); ++i)
    ultra_minus_tight.push_back(per_run_h["ultra"][i] - per_run_h["tight"][i]);
  const Spread d = spread(ultra_minus_tight);
  return {{"horizontal", h_ok},
          {"3d", d3_ok},
          {"ultra_minus_tight_h_m", {{"mean", d.mean}, {"std", d.std}, {"runs", d.n}}},
          {"ultra_beats_tight_h", paired_verdict(per_run_h["ultra"], per_run_h["tight"])},
          {"ultra_beats_tight_3d", paired_verdict(per_run_3d["ultra"], per_run_3d["tight"])},
          {"tight_beats_loose_3d", paired_verdict(per_run_3d["tight"], per_run_3d["loose"])},
          {"ultra_beats_loose_3d", paired_verdict(per_run_3d["ultra"], per_run_3d["loose"])}};
}

}  // namespace

BenchReport coupling_report(const CouplingSweepSettings& o, const std::vector<nlohmann::json>& points,
                            const std::optional<std::string>& kept_in) {
  const CouplingPointSettings& pt = o.point;
  BenchReport report(
      fmt::format("GNSS/INS coupling: position error against truth (paper 003), errors: {}", pt.errors),
      {"trajectory", "mode", "n_at_m", "e_at_m", "d_at_m", "paper_n_m", "paper_e_m", "paper_d_m", "rms_h_mean_m",
       "rms_h_std_m", "rms_3d_mean_m", "rms_3d_std_m", "rms_v_settled_m", "in_mode_pct"});
  for (const char* c : {"n_at_m", "e_at_m", "d_at_m", "paper_n_m", "paper_e_m", "paper_d_m", "rms_h_mean_m",
                        "rms_h_std_m", "rms_3d_mean_m", "rms_3d_std_m", "rms_v_settled_m"})
    report.set_precision(c, 3);
  report.set_precision("in_mode_pct", 0);
  int holds_h = 0, holds_3d = 0, checked = 0;
  nlohmann::json ordering = nlohmann::json::object();
  for (const auto& traj : o.trajectories) {
    const nlohmann::json verdict = add_trajectory_rows(report, o, traj, points);
    if (verdict.is_null()) continue;
    ++checked;
    holds_h += verdict["horizontal"].get<bool>() ? 1 : 0;
    holds_3d += verdict["3d"].get<bool>() ? 1 : 0;
    ordering[traj] = verdict;
  }
  report.add_note("runs", o.runs);
  report.add_note("errors", pt.errors);
  report.add_note("imu_grade", pt.imu_grade);
  report.add_note("scenario", source_relative(pt.base_scenario));
  report.add_note(
      "receiver_models",
      fmt::format("ionosphere {}, troposphere {}{}{}", to_string(pt.atmosphere.ionosphere),
                  to_string(pt.atmosphere.troposphere), pt.filter_troposphere ? ", zenith troposphere state" : "",
                  pt.filter_ionosphere ? ", ionosphere scale state" : ""));
  report.add_note("scoring", fmt::format("n/e/d_at: north/east/down 1-sigma over runs at t = {} s (RMS across runs); "
                                         "rms_h/rms_3d: each run's RMS over every epoch from {} s to {} s, mean and "
                                         "standard deviation over the runs; rms_v_settled: each run's vertical "
                                         "RMS from {} s after a delay model mismatch was found to the end, mean over "
                                         "the runs that found one (nan: none did)",
                                         o.score_at_s, o.score_from_s, pt.duration_s, kSettleAfterMismatchS));
  report.add_note("ordering_ultra_le_tight_le_loose_horizontal",
                  fmt::format("{} of {} trajectories", holds_h, checked));
  report.add_note("ordering_ultra_le_tight_le_loose_3d", fmt::format("{} of {} trajectories", holds_3d, checked));
  report.add_note("paired", ordering);
  report.add_note("mismatch_found", mismatch_counts(points, pt.modes));
  if (kept_in) report.add_note("out", source_relative(*kept_in));
  return report;
}

nlohmann::json mismatch_counts(const std::vector<nlohmann::json>& points, const std::vector<std::string>& modes) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& mode : modes) {
    int recorded = 0, troposphere = 0, ionosphere = 0;
    for (const auto& p : points) {
      const auto& m = p["modes"][mode];
      if (!m.contains("troposphere_mismatch_s")) continue;
      ++recorded;
      troposphere += m["troposphere_mismatch_s"].is_null() ? 0 : 1;
      ionosphere += m["ionosphere_mismatch_s"].is_null() ? 0 : 1;
    }
    out[mode] = recorded == 0 ? nlohmann::json("-")
                              : nlohmann::json(fmt::format("troposphere {} / ionosphere {} of {} runs", troposphere,
                                                           ionosphere, recorded));
  }
  return out;
}

void write_coupling_csv(const std::string& path, const std::vector<nlohmann::json>& points) {
  try {  // complete or absent (a full disk: an error naming it, nothing left)
    TextOutputFile csv(path);
    csv.write("trajectory,run,requested_mode,t_s,mode,valid,error_n_m,error_e_m,error_d_m,velocity_error_mps\n");
    for (const auto& p : points)
      for (const auto& [mode, r] : p["modes"].items())
        for (const auto& e : r["epochs"])
          csv.write(fmt::format("{},{},{},{:.2f},{},{},{:.4f},{:.4f},{:.4f},{:.4f}\n",
                                p["trajectory"].get<std::string>(), p["run"].get<int>(), mode, e[0].get<double>(),
                                e[1].get<std::string>(), e[2].get<bool>() ? 1 : 0, e[3].get<double>(),
                                e[4].get<double>(), e[5].get<double>(), e[6].get<double>()));
    csv.commit();
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

}  // namespace deepnav::bench
