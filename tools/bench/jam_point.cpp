#include "tools/bench/jam_point.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "aiding/navigation_session.hpp"
#include "ins/frames.hpp"
#include "ins/imu_file.hpp"
#include "ins/imu_model.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/products/truth_file.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/scenario.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/bench/child_process.hpp"
#include "ins/input_error.hpp"
#include "tools/bench/receiver_modes.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// A tracked channel's carrier must follow the true Doppler within this.
constexpr double kDopplerToleranceHz = 10.0;
/// A second, lower C/N0 floor for the signal fraction, applied to the mean of a channel's
/// C/N0 estimates over the last second: about 10 dB above that mean for a correlator without
/// signal (0 to 5 dB-Hz on every channel at J/S 70 dB), so a channel above it sees its
/// satellite.
constexpr double kSignalFloorDbhz = 15.0;
/// The receiver's C/N0 estimate averages over 2 s: skip that long after the onset.
constexpr double kCn0SettleS = 2.0;

/// A CSV file as rows of strings with a column lookup by header name.
struct Csv {
  std::map<std::string, std::size_t> column;
  std::vector<std::vector<std::string>> rows;
  explicit Csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError("cannot read '" + path + "'");
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header = split(line);
    for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
    while (std::getline(in, line))
      if (!line.empty()) rows.push_back(split(line));
  }
  std::size_t at(const std::string& name, const std::string& path) const {
    const auto it = column.find(name);
    if (it == column.end()) throw InputError("'" + path + "' has no column '" + name + "'");
    return it->second;
  }
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) out.push_back(cell);
    return out;
  }
};

double number(const std::vector<std::string>& row, std::size_t i) { return i < row.size() ? std::stod(row[i]) : kNaN; }

struct ErrorStats {
  double rms = kNaN, max = kNaN;
  static ErrorStats of(const std::vector<double>& v) {
    ErrorStats s;
    if (v.empty()) return s;
    double sum2 = 0.0;
    for (double x : v) sum2 += x * x;
    s.rms = std::sqrt(sum2 / static_cast<double>(v.size()));
    s.max = *std::max_element(v.begin(), v.end());
    return s;
  }
};

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// One correlator integration, as the run's tracking product has it.
struct TrackingRow {
  double t_s;  ///< start of the integration (first sample / fs)
  int prn;
  ChannelState state;
  double integration_s, doppler_hz, cn0_dbhz;
  std::optional<bool> aided_lock;  ///< steered channel: the aided lock criterion
};

/// One solution of the run (its pvt.csv row).
struct SolutionRow {
  double t_s;
  Eigen::Vector3d r_ecef_m;
  double lat_rad, lon_rad;
  std::string mode;
};

/// Keeps what the figures need from the run (a jam point is tens of seconds long).
class JamRecorder : public ProductSink {
 public:
  explicit JamRecorder(double fs_hz) : fs_hz_(fs_hz) {}
  void on_epoch(const NavigationEpoch& e) override {
    if (!e.solution.valid) return;
    solutions.push_back({e.receiver.t_s, e.solution.r_ecef_m, e.solution.llh.lat_rad, e.solution.llh.lon_rad,
                         std::string(e.mode)});
  }
  void on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) override {
    tracking.push_back({static_cast<double>(e.first_sample) / fs_hz_, e.prn, ch.state, e.integration_s,
                        e.carrier_doppler_hz, ch.cn0_dbhz, ch.aided_lock});
  }
  std::vector<TrackingRow> tracking;
  std::vector<SolutionRow> solutions;

 private:
  double fs_hz_;
};

/// When each satellite is tracked in the jammed window, from tracking.csv and the
/// synthesizer's sat_truth.csv (true Doppler, 10 Hz). An integration counts as tracked when
/// the channel is in the tracking state, its carrier is within 10 Hz of the true Doppler,
/// and its C/N0 estimate has not stayed below the receiver's loss threshold (22 dB-Hz) for
/// the receiver's loss time (1 s): the rule by which scalar tracking drops a channel. A
/// channel the ultra-tight filter steers is judged by the aided lock criterion instead (a
/// measurement within the last second: an integration whose signal is detected and whose
/// code discriminator noise is no worse than at 18 dB-Hz over 10 ms), since its long
/// integrations measure below 22 dB-Hz; the aided modes hold channels open without signal
/// (their NCOs then follow the INS, so the carrier stays near the true Doppler regardless),
/// which neither rule counts.
struct ChannelTimeline {
  struct Span {
    double t_s, integration_s, cn0_dbhz;
    bool tracked;      ///< under the receiver's loss rule (22 dB-Hz for 1 s)
    bool with_signal;  ///< following, with a mean C/N0 over the last second of at least kSignalFloorDbhz
  };
  std::map<int, std::vector<Span>> spans;  ///< per PRN, in time order; PRNs of the truth only
  std::vector<int> prns;                   ///< every satellite the synthesizer transmitted

  /// Satellites whose latest integration starting in [t - 1 s, t) is tracked.
  int tracked_at(double t) const {
    int n = 0;
    for (const auto& [prn, v] : spans) {
      const auto it = std::lower_bound(v.begin(), v.end(), t, [](const Span& s, double x) { return s.t_s < x; });
      if (it == v.begin()) continue;
      const Span& last = *std::prev(it);
      if (last.t_s >= t - 1.0 && last.tracked) ++n;
    }
    return n;
  }
};

ChannelTimeline channel_timeline(const std::vector<TrackingRow>& tracking, const std::string& sat_truth_path,
                                 double window_start_s, double window_end_s) {
  const Csv truth(sat_truth_path);
  const std::size_t t_col = truth.at("t_s", sat_truth_path), prn_col = truth.at("prn", sat_truth_path),
                    dop_col = truth.at("doppler_hz", sat_truth_path);
  std::map<int, std::vector<std::pair<double, double>>> doppler;
  for (const auto& r : truth.rows) doppler[std::stoi(r[prn_col])].emplace_back(number(r, t_col), number(r, dop_col));
  const auto true_doppler = [&](int prn, double t) {
    const auto& v = doppler[prn];
    const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
    return it == v.end() ? v.back().second : it->second;
  };
  const TrackingConfig loss;  // the receiver's loss-of-lock rule
  ChannelTimeline timeline;
  for (const auto& [prn, v] : doppler) timeline.prns.push_back(prn);
  std::map<int, double> below_since;  // per PRN: start of the current run of C/N0 below the loss threshold
  std::map<int, std::deque<std::pair<double, double>>> last_second;  // per PRN: (t, C/N0) over the last second
  std::map<int, double> last_second_sum;
  for (const TrackingRow& r : tracking) {
    const double t = r.t_s;
    const int prn = r.prn;
    if (!doppler.count(prn) || t >= window_end_s) continue;
    const double cn0 = r.cn0_dbhz;
    if (!(cn0 < loss.lost_cn0_dbhz))
      below_since.erase(prn);
    else
      below_since.try_emplace(prn, t);
    // A channel its filter steers and judges (ultra-tight) is held to that filter's lock
    // criterion instead: a measurement within the last second.
    const bool faded = r.aided_lock ? !*r.aided_lock : below_since.count(prn) && t - below_since[prn] >= loss.lost_after_s;
    auto& recent = last_second[prn];
    double& recent_sum = last_second_sum[prn];
    recent.emplace_back(t, cn0);
    recent_sum += cn0;
    while (recent.front().first < t - loss.lost_after_s) {
      recent_sum -= recent.front().second;
      recent.pop_front();
    }
    const bool no_signal = recent_sum / static_cast<double>(recent.size()) < kSignalFloorDbhz;
    // Kept from one second before the window, so the first epochs see their channels.
    if (t < window_start_s - 1.0) continue;
    const bool following =
        r.state == ChannelState::tracking && std::abs(r.doppler_hz - true_doppler(prn, t)) <= kDopplerToleranceHz;
    timeline.spans[prn].push_back({t, r.integration_s, cn0, following && !faded, following && !no_signal});
  }
  for (auto& [prn, v] : timeline.spans)
    std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
  return timeline;
}

/// Per-satellite tracked fraction and mean C/N0 estimate in the jammed window.
nlohmann::json channel_figures(const ChannelTimeline& timeline, double window_start_s, double window_end_s) {
  nlohmann::json channels = nlohmann::json::object();
  const double window = window_end_s - window_start_s;
  for (int prn : timeline.prns) {
    double tracked_s = 0.0, signal_s = 0.0, cn0_sum = 0.0;
    int cn0_count = 0;
    if (const auto found = timeline.spans.find(prn); found != timeline.spans.end()) {
      for (const auto& s : found->second) {
        if (s.t_s < window_start_s) continue;
        if (s.with_signal) signal_s += s.integration_s;
        if (!s.tracked) continue;
        tracked_s += s.integration_s;
        if (s.t_s >= window_start_s + kCn0SettleS) {
          cn0_sum += s.cn0_dbhz;
          ++cn0_count;
        }
      }
    }
    const double cn0 = cn0_count ? cn0_sum / cn0_count : kNaN;
    channels[std::to_string(prn)] = {{"tracked_fraction", std::min(1.0, tracked_s / window)},
                                     {"signal_fraction", std::min(1.0, signal_s / window)},
                                     {"cn0_dbhz", finite_or_null(cn0)}};
  }
  return channels;
}

/// Horizontal/vertical error and fix availability of the run's solutions in the jammed
/// window. Every solution the run gives counts for the error (an aided mode's coasting INS
/// included); only GNSS fixes count for availability: a solution not in INS coast with at
/// least four satellites tracked (as in ChannelTimeline) at its epoch.
nlohmann::json solution_figures(const std::vector<SolutionRow>& solutions_in, const std::string& truth_path,
                                const ChannelTimeline& timeline, double window_start_s, double window_end_s) {
  constexpr int kMinSatellites = 4;
  const TruthFile truth(truth_path);
  std::vector<double> horizontal, vertical;
  std::map<std::string, double> epochs_in_mode;
  int solutions = 0, gnss_fixes = 0;
  for (const SolutionRow& r : solutions_in) {
    const double ts = r.t_s;
    if (ts < window_start_s || ts >= window_end_s) continue;
    const auto ref = truth.at(ts);
    if (!ref) continue;
    ++solutions;
    epochs_in_mode[r.mode] += 1.0;
    if (r.mode != "coast" && timeline.tracked_at(ts) >= kMinSatellites) ++gnss_fixes;
    const Eigen::Vector3d d = C_e_n(r.lat_rad, r.lon_rad) * (r.r_ecef_m - ref->r_ecef_m);
    horizontal.push_back(d.head<2>().norm());
    vertical.push_back(std::abs(d.z()));
  }
  // Fixes come at whole seconds (1 Hz): the epochs expected in [start, end). The epoch at
  // the very end of the samples may not be formed, so it is not counted either way.
  const double expected = std::ceil(window_end_s) - std::ceil(window_start_s);
  if (expected - solutions > 0.0) epochs_in_mode["none"] = expected - solutions;
  const ErrorStats h = ErrorStats::of(horizontal), v = ErrorStats::of(vertical);
  return {{"solutions", solutions},
          {"fixes", gnss_fixes},
          {"solution_availability", std::min(1.0, solutions / expected)},
          {"fix_availability", std::min(1.0, gnss_fixes / expected)},
          {"epochs_in_mode", epochs_in_mode},
          {"horizontal_rms_m", finite_or_null(h.rms)},
          {"horizontal_max_m", finite_or_null(h.max)},
          {"vertical_rms_m", finite_or_null(v.rms)},
          {"vertical_max_m", finite_or_null(v.max)}};
}

/// Adds the summary over channels and the pass/fail verdict.
void judge(nlohmann::json& fig) {
  const FailureCriteria c;
  double sum = 0.0, min = 1.0, cn0_sum = 0.0, signal_sum = 0.0;
  int n = 0, n_cn0 = 0;
  for (const auto& [prn, ch] : fig["channels"].items()) {
    const double f = ch["tracked_fraction"].get<double>();
    sum += f;
    min = std::min(min, f);
    signal_sum += ch.value("signal_fraction", 0.0);
    ++n;
    if (!ch["cn0_dbhz"].is_null()) {
      cn0_sum += ch["cn0_dbhz"].get<double>();
      ++n_cn0;
    }
  }
  fig["tracked_fraction_mean"] = n ? sum / n : 0.0;
  fig["tracked_fraction_min"] = n ? min : 0.0;
  fig["signal_fraction_mean"] = n ? signal_sum / n : 0.0;
  fig["cn0_mean_dbhz"] = n_cn0 ? nlohmann::json(cn0_sum / n_cn0) : nlohmann::json(nullptr);
  std::vector<std::string> reasons;
  const auto& s = fig["solution"];
  if (s["fix_availability"].get<double>() < c.min_fix_availability) reasons.push_back("GNSS fixes missing");
  const auto over = [&](const char* key) { return !s[key].is_null() && s[key].get<double>() > c.max_error_m; };
  if (over("horizontal_max_m") || over("vertical_max_m")) reasons.push_back("error over 10 m");
  if (fig["tracked_fraction_mean"].get<double>() < c.min_tracked_fraction) reasons.push_back("tracking lost");
  std::string joined;
  for (const auto& r : reasons) joined += (joined.empty() ? "" : "; ") + r;
  fig["failed"] = !reasons.empty();
  fig["failure"] = joined;
}

}  // namespace

JammerConfig benchmark_jammer(const std::string& type, double js_db, double onset_s) {
  JammerConfig j;
  try {
    j.type = parse_jammer_type(type);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--jammer: ") + e.what());
  }
  j.js_db = js_db;
  j.start_s = onset_s;
  switch (j.type) {
    case JammerType::cw:
      j.center_offset_hz = 151.7e3;  // between C/A spectral lines, inside the main lobe
      break;
    case JammerType::chirp:
      j.bandwidth_hz = 2.0e6;
      j.sweep_period_s = 1e-3;
      break;
    case JammerType::wideband:
      j.bandwidth_hz = 2.046e6;  // the C/A main lobe
      break;
    case JammerType::pulsed:
      j.bandwidth_hz = 2.046e6;
      j.duty_cycle = 0.1;
      j.pulse_rate_hz = 3000.0;
      break;
  }
  return j;
}

std::string point_id(const JamPoint& p) {
  const aiding::LongIntegrationConfig defaults;
  const bool own_integration = p.long_integration.coherent_ms != defaults.coherent_ms ||
                               p.long_integration.noncoherent_ms != defaults.noncoherent_ms;
  return fmt::format("{}_{}_js{:05.1f}_{}{}_{}_s{}{}", fs::path(p.scenario).stem().string(), p.jammer, p.js_db, p.mode,
                     p.long_integration.assist_data_bits ? "-assisted-bits" : "", p.mitigation, p.seed,
                     own_integration ? fmt::format("_c{}n{}", p.long_integration.coherent_ms,
                                                   p.long_integration.noncoherent_ms)
                                     : "");
}

std::string point_dir(const std::string& out_dir, const JamPoint& p) {
  return (fs::path(out_dir) / "points" / point_id(p)).string();
}

bool point_done(const std::string& out_dir, const JamPoint& p) {
  return fs::exists(fs::path(point_dir(out_dir, p)) / "point.json");
}

nlohmann::json run_jam_point(const JamPoint& p, const std::string& out_dir) {
  const auto start = std::chrono::steady_clock::now();
  const ReceiverMode& mode = find_receiver_mode(p.mode);
  Scenario sc;
  try {
    sc = load_scenario(p.scenario, DEEPNAV_SOURCE_DIR);
    sc.seed = p.seed;
    if (!(p.onset_s >= 0.0 && p.onset_s < sc.duration_s))
      throw InputError(fmt::format("--onset {} s: expected within the scenario's {} s", p.onset_s, sc.duration_s));
    sc.jammers = {benchmark_jammer(p.jammer, p.js_db, p.onset_s)};
    if (mode.needs_imu && !sc.imu.enabled)
      throw InputError(fmt::format("receiver mode '{}' needs an IMU, but scenario '{}' has no imu: section "
                                  "(e.g. imu: {{grade: tactical, rate_hz: 100}})",
                                  p.mode, p.scenario));
    validate_scenario(sc);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    throw InputError(e.what());
  }
  const fs::path dir = point_dir(out_dir, p);
  const fs::path work = dir / "work";
  fs::create_directories(work);
  SynthesisOptions so;
  so.threads = 1;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run((work / "sim").string(), so);

  // The run, in-process; `command` records the equivalent `deepnav run` for a rerun by hand.
  std::vector<std::string> argv = {"deepnav", "run", "--input", s.if_path, "--format", std::string(to_string(sc.format)),
                                   "--fs", fmt::format("{}", sc.sample_rate_hz), "--if", fmt::format("{}", sc.if_hz),
                                   "--week", std::to_string(sc.start_time.week), "--iono-from", sc.nav_file,
                                   "--ephemeris-from", sc.nav_file, "--truth", s.truth_path, "--mitigation",
                                   p.mitigation, "--coherent-ms", std::to_string(p.long_integration.coherent_ms),
                                   "--noncoherent-ms", std::to_string(p.long_integration.noncoherent_ms),
                                   "--out", (work / "run").string()};
  if (p.long_integration.assist_data_bits) argv.push_back("--assist-data-bits");
  const RunImu imu{s.imu_path, sc.imu.grade, sc.imu.grades_file, sc.imu.lever_arm_m};
  for (const auto& a : receiver_mode_run_arguments(mode, imu, p.scenario)) argv.push_back(a);
  JamRecorder recorder(sc.sample_rate_hz);
  nlohmann::json mode_changes = nlohmann::json::array(), seconds_in_mode;
  {
    FileSampleSource source(synthesized_source(sc, s));
    const aiding::NavMode nav_mode = aiding::parse_nav_mode(p.mode);
    aiding::NavigationSessionConfig cfg = scenario_session_config(sc, nav_mode);
    cfg.mitigation.mode = parse_mitigation_mode(p.mitigation);
    cfg.navigator.ultra.long_integration = p.long_integration;
    aiding::NavigationSession session(cfg, source, scenario_imu_log(s, nav_mode), sc.duration_s);
    session.run({&recorder});
    if (const aiding::AidedReceiver* aided = session.aided()) {
      mode_changes = aiding::mode_changes_json(aided->mode_changes());
      seconds_in_mode = session.seconds_in_mode();
    }
  }

  nlohmann::json fig = {{"id", point_id(p)},
                        {"scenario", fs::path(p.scenario).stem().string()},
                        {"jammer", p.jammer},
                        {"js_db", p.js_db},
                        {"mode", p.mode},
                        {"mitigation", p.mitigation},
                        {"seed", p.seed},
                        {"onset_s", p.onset_s},
                        {"duration_s", sc.duration_s},
                        {"adc_bits", sc.adc.bits},
                        {"coherent_ms", p.long_integration.coherent_ms},
                        {"noncoherent_ms", p.long_integration.noncoherent_ms},
                        {"assisted_data_bits", p.long_integration.assist_data_bits},
                        {"command", shell_command_line(argv)}};
  const ChannelTimeline timeline = channel_timeline(recorder.tracking, s.sat_truth_path, p.onset_s, sc.duration_s);
  fig["channels"] = channel_figures(timeline, p.onset_s, sc.duration_s);
  fig["solution"] = solution_figures(recorder.solutions, s.truth_path, timeline, p.onset_s, sc.duration_s);
  judge(fig);
  fig["mode_changes"] = mode_changes;
  if (!seconds_in_mode.is_null()) fig["seconds_in_mode"] = seconds_in_mode;
  fs::remove_all(work);
  fig["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  TextOutputFile out((dir / "point.json").string());
  out.write(fig.dump(2) + "\n");
  out.commit();
  return fig;
}

}  // namespace deepnav::bench
