#include "tools/cli/snap_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numbers>

namespace deepnav::cli {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

nlohmann::json optional_number(bool present, double value) { return present ? nlohmann::json(value) : nullptr; }

bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

nlohmann::json satellite_json(const SnapshotSignal& s, const CoarseTimeFix& fix) {
  const bool used = contains(fix.used_prns, s.prn);
  nlohmann::json j = {
      {"prn", s.prn},
      {"code_phase_chips", s.code_phase_chips},
      {"doppler_hz", s.doppler_hz},
      {"cn0_dbhz", s.cn0_dbhz},
      {"refined", s.refined},
      {"used", used},
      {"excluded", contains(fix.excluded_prns, s.prn)},
      {"predicted_doppler_hz", s.predicted_doppler_hz ? nlohmann::json(*s.predicted_doppler_hz) : nullptr},
      {"residual_m", used ? nlohmann::json(fix.residuals_m.at(s.prn)) : nullptr},
      {"elevation_deg", used ? nlohmann::json(fix.elevation_rad.at(s.prn) * kRadToDeg) : nullptr}};
  if (!s.refinement_note.empty()) j["refinement_note"] = s.refinement_note;
  return j;
}

std::string prn_list(const std::vector<int>& prns) { return fmt::format("{}", fmt::join(prns, ",")); }

}  // namespace

std::string quality_flag(const CoarseTimeFix& fix) {
  if (!fix.valid) return "none";
  return fix.quality.degrees_of_freedom >= 2 ? "good" : "marginal";
}

nlohmann::json snapshot_json(const SnapEntry& e) {
  const CoarseTimeFix& fix = e.result.fix;
  nlohmann::json satellites = nlohmann::json::array();
  for (const SnapshotSignal& s : e.result.signals) satellites.push_back(satellite_json(s, fix));
  nlohmann::json j = {
      {"t_s", e.t_s},
      {"length_ms", e.length_ms},
      {"time_hint", {{"week", e.t_hint.week}, {"sow", e.t_hint.sow}}},
      {"lat_deg", optional_number(fix.valid, fix.llh.lat_rad * kRadToDeg)},
      {"lon_deg", optional_number(fix.valid, fix.llh.lon_rad * kRadToDeg)},
      {"height_m", optional_number(fix.valid, fix.llh.height_m)},
      {"time_correction_s", optional_number(fix.valid, fix.coarse_time_correction_s)},
      {"gps_time", fix.valid ? nlohmann::json{{"week", fix.receive_time.week}, {"sow", fix.receive_time.sow}}
                             : nlohmann::json(nullptr)},
      {"clock_bias_m", optional_number(fix.valid, fix.clock_bias_m)},
      {"satellites", satellites},
      {"searched_prns", e.result.searched_prns},
      {"used_prns", fix.used_prns},
      {"excluded_prns", fix.excluded_prns},
      {"without_ephemeris", fix.without_ephemeris},
      {"residual_rms_m", optional_number(fix.valid, fix.quality.residual_rms_m)},
      {"chi_square", optional_number(fix.valid, fix.quality.chi_square)},
      {"chi_square_threshold", optional_number(fix.valid, fix.quality.chi_square_threshold)},
      {"degrees_of_freedom", optional_number(fix.valid, fix.quality.degrees_of_freedom)},
      {"hdop", optional_number(fix.valid, fix.dops.hdop)},
      {"pdop", optional_number(fix.valid, fix.dops.pdop)},
      {"start", fix.valid ? nlohmann::json(to_string(fix.start)) : nlohmann::json(nullptr)},
      {"quality", quality_flag(fix)},
      {"reason", fix.valid ? nlohmann::json(nullptr) : nlohmann::json(fix.reason)},
      {"suspect_hint", to_string(fix.suspect)},
      {"solve_cpu_ms", e.solve_cpu_ms}};
  if (!fix.repaired_ms.empty()) {
    nlohmann::json repaired = nlohmann::json::object();
    for (const auto& [prn, ms] : fix.repaired_ms) repaired[std::to_string(prn)] = ms;
    j["repaired_ms"] = repaired;
  }
  return j;
}

nlohmann::json snap_document(const std::string& input, const std::string& nav, const std::vector<SnapEntry>& entries) {
  nlohmann::json snapshots = nlohmann::json::array();
  for (const auto& e : entries) snapshots.push_back(snapshot_json(e));
  return {{"input", input}, {"nav", nav}, {"snapshots", snapshots}};
}

std::string snap_table(const std::vector<SnapEntry>& entries) {
  std::string out = fmt::format("{:>8} {:>12} {:>13} {:>9} {:>10} {:>5} {:>9}  {}\n", "t_s", "lat_deg", "lon_deg",
                                "height_m", "dt_s", "sats", "quality", "used PRNs / reason");
  for (const auto& e : entries) {
    const CoarseTimeFix& f = e.result.fix;
    if (f.valid)
      out += fmt::format("{:>8.3f} {:>12.7f} {:>13.7f} {:>9.1f} {:>10.3f} {:>5} {:>9}  {}\n", e.t_s,
                         f.llh.lat_rad * kRadToDeg, f.llh.lon_rad * kRadToDeg, f.llh.height_m,
                         f.coarse_time_correction_s, f.used_prns.size(), quality_flag(f), prn_list(f.used_prns));
    else
      out += fmt::format("{:>8.3f} {:>12} {:>13} {:>9} {:>10} {:>5} {:>9}  {}\n", e.t_s, "-", "-", "-", "-",
                         e.result.signals.size(), "none", f.reason);
  }
  return out;
}

std::string signals_table(const SnapshotResult& result) {
  std::string out = fmt::format("{:>4} {:>11} {:>17} {:>9}\n", "PRN", "doppler_hz", "code_phase_chips", "cn0_dbhz");
  for (const SnapshotSignal& s : result.signals)
    out += fmt::format("{:>4} {:>11.1f} {:>17.4f} {:>9.1f}\n", s.prn, s.doppler_hz, s.code_phase_chips, s.cn0_dbhz);
  return out;
}

}  // namespace deepnav::cli
