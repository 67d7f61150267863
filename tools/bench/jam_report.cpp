#include "tools/bench/jam_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "ins/input_error.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/jam_judge.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;

std::string cell(const nlohmann::json& v, int decimals) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_float()) return fmt::format("{:.{}f}", v.get<double>(), decimals);
  if (v.is_number()) return std::to_string(v.get<long long>());
  return v.get<std::string>();
}

void write_runs_csv(const std::vector<nlohmann::json>& points, const std::string& out_dir) {
  TextOutputFile csv((fs::path(out_dir) / "runs.csv").string());
  csv.write(
      "scenario,jammer,js_db,mode,mitigation,seed,adc_bits,tracked_fraction_mean,tracked_fraction_min,"
      "signal_fraction_mean,cn0_mean_dbhz,"
      "fix_availability,solution_availability,epochs_in_mode,horizontal_rms_m,horizontal_max_m,vertical_rms_m,vertical_"
      "max_m,failed,failure,"
      "tracked_fraction_by_prn,cn0_by_prn_dbhz,wall_s\n");
  for (const auto& p : points) {
    const auto& s = p["solution"];
    std::string tracked, cn0, modes;
    if (s.contains("epochs_in_mode"))
      for (const auto& [m, n] : s["epochs_in_mode"].items())
        modes += fmt::format("{}{}:{:.0f}", modes.empty() ? "" : " ", m, n.get<double>());
    for (const auto& [prn, ch] : p["channels"].items()) {
      tracked += fmt::format("{}{}:{:.3f}", tracked.empty() ? "" : " ", prn, ch["tracked_fraction"].get<double>());
      cn0 += fmt::format("{}{}:{}", cn0.empty() ? "" : " ", prn, cell(ch["cn0_dbhz"], 1));
    }
    csv.write(fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", cell(p["scenario"], 0),
        cell(p["jammer"], 0), cell(p["js_db"], 1), cell(p["mode"], 0), cell(p["mitigation"], 0), cell(p["seed"], 0),
        cell(p["adc_bits"], 0), cell(p["tracked_fraction_mean"], 3), cell(p["tracked_fraction_min"], 3),
        cell(p.value("signal_fraction_mean", nlohmann::json()), 3), cell(p["cn0_mean_dbhz"], 2),
        cell(s["fix_availability"], 3), cell(s.value("solution_availability", nlohmann::json()), 3), modes,
        cell(s["horizontal_rms_m"], 3), cell(s["horizontal_max_m"], 3), cell(s["vertical_rms_m"], 3),
        cell(s["vertical_max_m"], 3), cell(p["failed"], 0), cell(p["failure"], 0), tracked, cn0, cell(p["wall_s"], 1)));
  }
  csv.commit();
}

using SeriesKey = std::tuple<std::string, std::string, std::string, std::string>;  // scenario, jammer, mode, mitigation

/// One series' points, J/S by J/S.
struct Series {
  double js_min = 1e300, js_max = -1e300;
  std::map<std::uint64_t, double> first_failure;  ///< per seed; kNoJamFailure when every J/S passed
  std::map<std::uint64_t, std::string> reason;
  /// per seed: first J/S at which the satellites see their signal (C/N0 at least 15
  /// dB-Hz) less than half of the time; kNoJamFailure when never
  std::map<std::uint64_t, double> first_signal_loss;
};

std::map<SeriesKey, Series> series_of(const std::vector<nlohmann::json>& points) {
  std::map<SeriesKey, Series> series;
  for (const auto& p : points) {  // sorted by J/S within a series: the first failure comes first
    Series& s = series[{p["scenario"], p["jammer"], p["mode"], p["mitigation"]}];
    const double js = p["js_db"].get<double>();
    const auto seed = p["seed"].get<std::uint64_t>();
    s.js_min = std::min(s.js_min, js);
    s.js_max = std::max(s.js_max, js);
    auto [it, inserted] = s.first_failure.try_emplace(seed, kNoJamFailure);
    if (p["failed"].get<bool>() && std::isinf(it->second)) {
      it->second = js;
      s.reason[seed] = p["failure"].get<std::string>();
    }
    auto [sig, sig_inserted] = s.first_signal_loss.try_emplace(seed, kNoJamFailure);
    if (p.contains("signal_fraction_mean") &&
        p["signal_fraction_mean"].get<double>() < FailureCriteria{}.min_tracked_fraction && std::isinf(sig->second))
      sig->second = js;
  }
  return series;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Over the seeds both series ran, so a mitigation is compared with the same noise and jammer.
std::string gain_over_none(const Series& mitigated, const Series& none) {
  std::vector<double> bv, tv;
  for (const auto& [seed, b] : none.first_failure)
    if (mitigated.first_failure.count(seed)) {
      bv.push_back(b);
      tv.push_back(mitigated.first_failure.at(seed));
    }
  const double b = bv.empty() ? kNoJamFailure : median(bv);
  const double m = tv.empty() ? kNoJamFailure : median(tv);
  if (bv.empty()) return "n/a (no common seed)";
  if (std::isinf(b)) return "n/a (none never failed)";
  if (std::isinf(m)) return fmt::format("> {:.1f}", mitigated.js_max - b);
  return fmt::format("{:.1f}", m - b);
}

std::string per_run_text(const JamThreshold& t) {
  std::string text;
  for (double v : t.first_failure_db) {
    if (!text.empty()) text += ' ';
    text += threshold_text(v, t.js_max_db);
  }
  return text;
}

std::string tested_text(const JamThreshold& t) { return fmt::format("{:g}..{:g}", t.js_min_db, t.js_max_db); }

constexpr const char* kThresholdsExplained =
    "\nA point fails when, from the jammer onset to the end, a solution is more than 10 m off the truth "
    "(horizontal or vertical; an aided mode's INS coast included), more than 5 % of the epochs have no GNSS "
    "fix (a solution not in INS coast with at least four satellites tracked), or the satellites are tracked "
    "less than half of the time on average. A satellite is tracked while its channel is in the tracking "
    "state, its carrier is within 10 Hz of the true Doppler and its C/N0 estimate has not been below 22 "
    "dB-Hz for 1 s (the scalar receiver's loss rule, applied to the channels of scalar, loose and tight); a "
    "channel the ultra-tight filter steers, by the aided lock criterion: one of its integrations within the last "
    "second had its signal detected and code discriminator noise no worse than at 18 dB-Hz over 10 ms (its long, "
    "data-wiped integrations measure well below 22 dB-Hz). Every mode starts with the "
    "broadcast ephemerides of the scenario's navigation file. \"> X\": no failure up to the highest J/S "
    "tested. \"Signal lost\": the first J/S at which the satellites' channels follow them (tracking state, "
    "carrier within 10 Hz) with a C/N0 estimate averaging at least 15 dB-Hz over the last second (about 10 dB "
    "above that average without signal) less than half of the time: how far the channels still see their "
    "signal, whatever the solution does.\n";

}  // namespace

std::vector<nlohmann::json> load_jam_points(const std::string& out_dir) {
  std::vector<nlohmann::json> points;
  const fs::path dir = fs::path(out_dir) / "points";
  if (!fs::is_directory(dir)) return points;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path file = entry.path() / "point.json";
    if (!fs::exists(file)) continue;
    std::ifstream in(file);
    try {
      points.push_back(nlohmann::json::parse(in));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("'{}' is not a point record: {}", file.string(), e.what()));
    }
  }
  std::sort(points.begin(), points.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
    const auto key = [](const nlohmann::json& p) {
      return std::make_tuple(p["scenario"].get<std::string>(), p["jammer"].get<std::string>(),
                             p["mode"].get<std::string>(), p["mitigation"].get<std::string>(),
                             p["seed"].get<std::uint64_t>(), p["js_db"].get<double>());
    };
    return key(a) < key(b);
  });
  return points;
}

std::vector<JamThreshold> jam_thresholds(const std::vector<nlohmann::json>& points) {
  const std::map<SeriesKey, Series> series = series_of(points);
  std::vector<JamThreshold> out;
  for (const auto& [key, s] : series) {
    JamThreshold& t = out.emplace_back();
    std::tie(t.scenario, t.jammer, t.mode, t.mitigation) = key;
    t.js_min_db = s.js_min;
    t.js_max_db = s.js_max;
    for (const auto& [seed, first] : s.first_failure) {
      t.first_failure_db.push_back(first);
      if (s.reason.count(seed) && t.failure.find(s.reason.at(seed)) == std::string::npos)
        t.failure += (t.failure.empty() ? "" : "; ") + s.reason.at(seed);
    }
    t.median_first_failure_db = median(t.first_failure_db);
    const auto none = series.find({t.scenario, t.jammer, t.mode, "none"});
    if (t.mitigation != "none" && none != series.end()) t.gain_over_none = gain_over_none(s, none->second);
    std::vector<double> signal_lost;
    for (const auto& [seed, v] : s.first_signal_loss) signal_lost.push_back(v);
    t.median_signal_lost_db = median(signal_lost);
  }
  return out;
}

std::string threshold_text(double t, double js_max) {
  return std::isinf(t) ? fmt::format("> {:.1f}", js_max) : fmt::format("{:.1f}", t);
}

BenchReport write_jam_report(const std::vector<nlohmann::json>& points, const std::string& out_dir) {
  write_runs_csv(points, out_dir);
  BenchReport report("Jamming thresholds: first J/S (dB) at which the solution leaves 10 m or tracking is lost",
                     {"scenario", "jammer", "mode", "mitigation", "js_tested_db", "runs", "first_failure_db",
                      "per_run_db", "gain_over_none_db", "failure", "signal_lost_db"});
  std::string md =
      "| scenario | jammer | mode | mitigation | J/S tested (dB) | runs | first failing J/S (dB, median) | per run | "
      "gain over none (dB, same seeds) | failure at threshold | signal lost at J/S (dB, median) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const JamThreshold& t : jam_thresholds(points)) {
    const std::string tested = tested_text(t), first = threshold_text(t.median_first_failure_db, t.js_max_db),
                      per_run = per_run_text(t), signal_lost = threshold_text(t.median_signal_lost_db, t.js_max_db);
    report.add_row({t.scenario, t.jammer, t.mode, t.mitigation, tested,
                    static_cast<long long>(t.first_failure_db.size()), first, per_run, t.gain_over_none, t.failure,
                    signal_lost});
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", t.scenario, t.jammer, t.mode,
                      t.mitigation, tested, t.first_failure_db.size(), first, per_run, t.gain_over_none, t.failure,
                      signal_lost);
  }
  md += kThresholdsExplained;
  TextOutputFile file((fs::path(out_dir) / "thresholds.md").string());
  file.write(md);
  file.commit();
  report.add_note("points", points.size());
  return report;
}

}  // namespace deepnav::bench
