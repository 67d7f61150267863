#include "tools/bench/jam_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <tuple>

#include "signals/text_output_file.hpp"
#include "ins/input_error.hpp"
#include "tools/bench/jam_point.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;
constexpr double kNoFailure = std::numeric_limits<double>::infinity();

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
      "fix_availability,solution_availability,epochs_in_mode,horizontal_rms_m,horizontal_max_m,vertical_rms_m,vertical_max_m,failed,failure,"
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
    csv.write(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", cell(p["scenario"], 0),
                          cell(p["jammer"], 0), cell(p["js_db"], 1), cell(p["mode"], 0), cell(p["mitigation"], 0),
                          cell(p["seed"], 0), cell(p["adc_bits"], 0), cell(p["tracked_fraction_mean"], 3),
                          cell(p["tracked_fraction_min"], 3), cell(p.value("signal_fraction_mean", nlohmann::json()), 3),
                          cell(p["cn0_mean_dbhz"], 2),
                          cell(s["fix_availability"], 3), cell(s.value("solution_availability", nlohmann::json()), 3),
                          modes, cell(s["horizontal_rms_m"], 3),
                          cell(s["horizontal_max_m"], 3), cell(s["vertical_rms_m"], 3), cell(s["vertical_max_m"], 3),
                          cell(p["failed"], 0), cell(p["failure"], 0), tracked, cn0, cell(p["wall_s"], 1)));
  }
  csv.commit();
}

using SeriesKey = std::tuple<std::string, std::string, std::string, std::string>;  // scenario, jammer, mode, mitigation

struct Series {
  double js_min = 1e300, js_max = -1e300;
  std::map<std::uint64_t, double> first_failure;  ///< per seed; kNoFailure when every J/S passed
  std::map<std::uint64_t, std::string> reason;
  /// per seed: first J/S at which the satellites see their signal (C/N0 at least 15
  /// dB-Hz) less than half of the time; kNoFailure when never
  std::map<std::uint64_t, double> first_signal_loss;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string threshold_text(double t, double js_max) {
  return std::isinf(t) ? fmt::format("> {:.1f}", js_max) : fmt::format("{:.1f}", t);
}

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

BenchReport write_jam_report(const std::vector<nlohmann::json>& points, const std::string& out_dir) {
  write_runs_csv(points, out_dir);
  std::map<SeriesKey, Series> series;
  for (const auto& p : points) {  // sorted by J/S within a series: the first failure comes first
    Series& s = series[{p["scenario"], p["jammer"], p["mode"], p["mitigation"]}];
    const double js = p["js_db"].get<double>();
    const auto seed = p["seed"].get<std::uint64_t>();
    s.js_min = std::min(s.js_min, js);
    s.js_max = std::max(s.js_max, js);
    auto [it, inserted] = s.first_failure.try_emplace(seed, kNoFailure);
    if (p["failed"].get<bool>() && std::isinf(it->second)) {
      it->second = js;
      s.reason[seed] = p["failure"].get<std::string>();
    }
    auto [sig, sig_inserted] = s.first_signal_loss.try_emplace(seed, kNoFailure);
    if (p.contains("signal_fraction_mean") && p["signal_fraction_mean"].get<double>() < FailureCriteria{}.min_tracked_fraction &&
        std::isinf(sig->second))
      sig->second = js;
  }
  BenchReport report("Jamming thresholds: first J/S (dB) at which the solution leaves 10 m or tracking is lost",
                     {"scenario", "jammer", "mode", "mitigation", "js_tested_db", "runs", "first_failure_db",
                      "per_run_db", "gain_over_none_db", "failure", "signal_lost_db"});
  std::string md =
      "| scenario | jammer | mode | mitigation | J/S tested (dB) | runs | first failing J/S (dB, median) | per run | "
      "gain over none (dB, same seeds) | failure at threshold | signal lost at J/S (dB, median) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, s] : series) {
    const auto& [scenario, jammer, mode, mitigation] = key;
    std::vector<double> values;
    std::string per_run, reasons;
    for (const auto& [seed, t] : s.first_failure) {
      values.push_back(t);
      per_run += (per_run.empty() ? "" : " ") + threshold_text(t, s.js_max);
      if (s.reason.count(seed) && reasons.find(s.reason.at(seed)) == std::string::npos)
        reasons += (reasons.empty() ? "" : "; ") + s.reason.at(seed);
    }
    const double t = median(values);
    std::string gain = "";
    const auto base = series.find({scenario, jammer, mode, "none"});
    if (mitigation != "none" && base != series.end()) {
      // Over the seeds both series ran, so a mitigation is compared with the same noise and jammer.
      std::vector<double> bv, tv;
      for (const auto& [seed, b] : base->second.first_failure)
        if (s.first_failure.count(seed)) {
          bv.push_back(b);
          tv.push_back(s.first_failure.at(seed));
        }
      const double b = bv.empty() ? kNoFailure : median(bv);
      const double m = tv.empty() ? kNoFailure : median(tv);
      if (bv.empty())
        gain = "n/a (no common seed)";
      else if (std::isinf(b))
        gain = "n/a (none never failed)";
      else if (std::isinf(m))
        gain = fmt::format("> {:.1f}", s.js_max - b);
      else
        gain = fmt::format("{:.1f}", m - b);
    }
    std::vector<double> signal_values;
    for (const auto& [seed, v] : s.first_signal_loss) signal_values.push_back(v);
    const std::string signal_lost = threshold_text(median(signal_values), s.js_max);
    const std::string tested = fmt::format("{:g}..{:g}", s.js_min, s.js_max);
    const std::string text = threshold_text(t, s.js_max);
    report.add_row({scenario, jammer, mode, mitigation, tested, static_cast<long long>(values.size()), text, per_run,
                    gain, reasons, signal_lost});
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", scenario, jammer, mode, mitigation,
                      tested, values.size(), text, per_run, gain, reasons, signal_lost);
  }
  md += "\nA point fails when, from the jammer onset to the end, a solution is more than 10 m off the truth "
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
  TextOutputFile file((fs::path(out_dir) / "thresholds.md").string());
  file.write(md);
  file.commit();
  report.add_note("points", points.size());
  return report;
}

}  // namespace deepnav::bench
