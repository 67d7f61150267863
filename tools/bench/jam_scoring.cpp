#include "tools/bench/jam_scoring.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <limits>
#include <sstream>

#include "ins/frames.hpp"
#include "ins/input_error.hpp"
#include "receiver/products/truth_file.hpp"

namespace deepnav::bench {
namespace {

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

/// A figure that exists only when finite: point.json writes null for the others, and the
/// verdict reads what point.json holds.
std::optional<double> finite(double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; }

struct ErrorStats {
  std::optional<double> rms, max;
  static ErrorStats of(const std::vector<double>& v) {
    ErrorStats s;
    if (v.empty()) return s;
    double sum2 = 0.0;
    for (double x : v) sum2 += x * x;
    s.rms = finite(std::sqrt(sum2 / static_cast<double>(v.size())));
    s.max = finite(*std::max_element(v.begin(), v.end()));
    return s;
  }
};

nlohmann::json figure(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

}  // namespace

void JamRecorder::on_epoch(const NavigationEpoch& e) {
  // Galileo channels by their observables over the interval since the last epoch (one the
  // filter steers is observable by its lock criterion, which the timeline then applies).
  const double t = e.receiver.t_s;
  if (last_epoch_t_s_ && t > *last_epoch_t_s_) {
    for (const ChannelObservation& o : e.receiver.observations)
      if (o.system == GnssSystem::galileo)
        tracking.push_back({*last_epoch_t_s_, o.satellite(), ChannelState::tracking, t - *last_epoch_t_s_, o.doppler_hz,
                            o.cn0_dbhz, o.aided_lock ? std::optional<bool>(true) : std::nullopt});
  }
  last_epoch_t_s_ = t;
  if (!e.solution.valid) return;
  solutions.push_back(
      {e.receiver.t_s, e.solution.r_ecef_m, e.solution.llh.lat_rad, e.solution.llh.lon_rad, std::string(e.mode)});
}

void JamRecorder::on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
  tracking.push_back({static_cast<double>(e.first_sample) / fs_hz_,
                      {GnssSystem::gps, e.prn},
                      ch.state,
                      e.integration_s,
                      e.carrier_doppler_hz,
                      ch.cn0_dbhz,
                      ch.aided_lock});
}

int ChannelTimeline::tracked_at(double t) const {
  int n = 0;
  for (const auto& [satellite, v] : spans) {
    const auto it = std::lower_bound(v.begin(), v.end(), t, [](const Span& s, double x) { return s.t_s < x; });
    if (it == v.begin()) continue;
    const Span& last = *std::prev(it);
    if (last.t_s >= t - 1.0 && last.tracked) ++n;
  }
  return n;
}

namespace {

/// A sat_truth.csv `prn` cell: "G05" / "E11" (mixed scenarios) or a GPS PRN alone.
SatelliteId truth_satellite(const std::string& cell, const std::string& path) {
  if (const auto id = parse_satellite_id(cell)) return *id;
  try {
    return {GnssSystem::gps, std::stoi(cell)};
  } catch (const std::exception&) {
    throw InputError(path + ": prn '" + cell + "': expected a GPS PRN or a satellite such as G05 or E11");
  }
}

}  // namespace

ChannelTimeline channel_timeline(const std::vector<TrackingRow>& tracking, const std::string& sat_truth_path,
                                 double window_start_s, double window_end_s, const std::vector<GnssSystem>& systems) {
  const Csv truth(sat_truth_path);
  const std::size_t t_col = truth.at("t_s", sat_truth_path), prn_col = truth.at("prn", sat_truth_path),
                    dop_col = truth.at("doppler_hz", sat_truth_path);
  std::map<SatelliteId, std::vector<std::pair<double, double>>> doppler;
  for (const auto& r : truth.rows) {
    const SatelliteId sat = truth_satellite(r[prn_col], sat_truth_path);
    if (includes_system(systems, sat.system)) doppler[sat].emplace_back(number(r, t_col), number(r, dop_col));
  }
  const auto true_doppler = [&](const SatelliteId& sat, double t) {
    const auto& v = doppler[sat];
    const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
    return it == v.end() ? v.back().second : it->second;
  };
  const TrackingConfig loss;  // the receiver's loss-of-lock rule
  ChannelTimeline timeline;
  for (const auto& [sat, v] : doppler) timeline.satellites.push_back(sat);
  std::map<SatelliteId, double> below_since;  // start of the current run of C/N0 below the loss threshold
  std::map<SatelliteId, std::deque<std::pair<double, double>>> last_second;  // (t, C/N0) over the last second
  std::map<SatelliteId, double> last_second_sum;
  for (const TrackingRow& r : tracking) {
    const double t = r.t_s;
    const SatelliteId& sat = r.satellite;
    if (!doppler.count(sat) || t >= window_end_s) continue;
    const double cn0 = r.cn0_dbhz;
    if (!(cn0 < loss.lost_cn0_dbhz)) below_since.erase(sat);
    else below_since.try_emplace(sat, t);
    // A channel its filter steers and judges (ultra-tight) is held to that filter's lock
    // criterion instead: a measurement within the last second.
    const bool faded =
        r.aided_lock ? !*r.aided_lock : below_since.count(sat) && t - below_since[sat] >= loss.lost_after_s;
    auto& recent = last_second[sat];
    double& recent_sum = last_second_sum[sat];
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
        r.state == ChannelState::tracking && std::abs(r.doppler_hz - true_doppler(sat, t)) <= kDopplerToleranceHz;
    timeline.spans[sat].push_back({t, r.integration_s, cn0, following && !faded, following && !no_signal});
  }
  for (auto& [sat, v] : timeline.spans)
    std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
  return timeline;
}

JamChannels channel_figures(const ChannelTimeline& timeline, double window_start_s, double window_end_s) {
  JamChannels channels;
  const double window = window_end_s - window_start_s;
  for (const SatelliteId& sat : timeline.satellites) {
    double tracked_s = 0.0, signal_s = 0.0, cn0_sum = 0.0;
    int cn0_count = 0;
    if (const auto found = timeline.spans.find(sat); found != timeline.spans.end()) {
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
    // GPS satellites keyed by their PRN alone, as GPS-only points always were.
    JamChannelFigures& ch = channels[sat.system == GnssSystem::gps ? std::to_string(sat.prn) : sat.to_string()];
    ch.tracked_fraction = std::min(1.0, tracked_s / window);
    ch.signal_fraction = std::min(1.0, signal_s / window);
    if (cn0_count) ch.cn0_dbhz = finite(cn0_sum / cn0_count);
  }
  return channels;
}

JamSolutionFigures solution_figures(const std::vector<SolutionRow>& solutions, const std::string& truth_path,
                                    const ChannelTimeline& timeline, double window_start_s, double window_end_s) {
  constexpr int kMinSatellites = 4;
  const TruthFile truth(truth_path);
  std::vector<double> horizontal, vertical;
  JamSolutionFigures f;
  for (const SolutionRow& r : solutions) {
    const double ts = r.t_s;
    if (ts < window_start_s || ts >= window_end_s) continue;
    const auto ref = truth.at(ts);
    if (!ref) continue;
    ++f.solutions;
    f.epochs_in_mode[r.mode] += 1.0;
    if (r.mode != "coast" && timeline.tracked_at(ts) >= kMinSatellites) ++f.fixes;
    const Eigen::Vector3d d = C_e_n(r.lat_rad, r.lon_rad) * (r.r_ecef_m - ref->r_ecef_m);
    horizontal.push_back(d.head<2>().norm());
    vertical.push_back(std::abs(d.z()));
  }
  // Fixes come at whole seconds (1 Hz): the epochs expected in [start, end). The epoch at
  // the very end of the samples may not be formed, so it is not counted either way.
  const double expected = std::ceil(window_end_s) - std::ceil(window_start_s);
  if (expected - f.solutions > 0.0) f.epochs_in_mode["none"] = expected - f.solutions;
  f.solution_availability = std::min(1.0, f.solutions / expected);
  f.fix_availability = std::min(1.0, f.fixes / expected);
  const ErrorStats h = ErrorStats::of(horizontal), v = ErrorStats::of(vertical);
  f.horizontal_rms_m = h.rms;
  f.horizontal_max_m = h.max;
  f.vertical_rms_m = v.rms;
  f.vertical_max_m = v.max;
  return f;
}

nlohmann::json to_json(const JamChannels& channels) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [prn, ch] : channels)
    out[prn] = {{"tracked_fraction", ch.tracked_fraction},
                {"signal_fraction", ch.signal_fraction},
                {"cn0_dbhz", figure(ch.cn0_dbhz)}};
  return out;
}

nlohmann::json to_json(const JamSolutionFigures& s) {
  return {{"solutions", s.solutions},
          {"fixes", s.fixes},
          {"solution_availability", s.solution_availability},
          {"fix_availability", s.fix_availability},
          {"epochs_in_mode", s.epochs_in_mode},
          {"horizontal_rms_m", figure(s.horizontal_rms_m)},
          {"horizontal_max_m", figure(s.horizontal_max_m)},
          {"vertical_rms_m", figure(s.vertical_rms_m)},
          {"vertical_max_m", figure(s.vertical_max_m)}};
}

}  // namespace deepnav::bench
