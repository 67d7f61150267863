#include "tools/bench/threshold_bench.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "aiding/navigation_session.hpp"
#include "ins/input_error.hpp"
#include "receiver/gnss_receiver.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/cycle_slip.hpp"

namespace deepnav::bench {
namespace {

using Series = std::map<int, std::vector<std::pair<double, double>>>;  // per PRN: (t, value)

/// The scenario with a C/N0 ramp and the length the ramp needs.
Scenario with_ramp(Scenario sc, const ThresholdBenchSettings& o) {
  const double ramp_s = (o.start_dbhz - o.end_dbhz) / o.rate_dbps;
  sc.duration_s = o.ramp_start_s + ramp_s;
  sc.cn0 = Cn0Spec{};
  sc.cn0.fixed_dbhz = o.start_dbhz;
  sc.cn0.ramp_start_s = o.ramp_start_s;
  sc.cn0.ramp_end_s = o.ramp_start_s + ramp_s;
  sc.cn0.ramp_delta_db = o.end_dbhz - o.start_dbhz;
  validate_scenario(sc);
  return sc;
}

std::string ramp_note(const ThresholdBenchSettings& o) {
  return fmt::format("{} dB-Hz until {} s, then -{} dB/s to {} dB-Hz", o.start_dbhz, o.ramp_start_s, o.rate_dbps,
                     o.end_dbhz);
}

/// How long a mode holds: to the epoch before the first after the ramp's start that has no
/// solution, is not in the mode, has fewer than four satellites' measurements or is more
/// than 10 m off horizontally (coasting on the INS alone does not count as holding).
struct ModeHold {
  double until_s;
  std::string failure = "held to the end of the ramp";
  double max_h_error_m = 0.0;  ///< before it stopped holding
};

ModeHold mode_hold(const AidedRunResult& r, aiding::NavMode mode, double ramp_start_s) {
  ModeHold hold{ramp_start_s};
  for (const auto& e : r.epochs) {
    if (e.t_s <= ramp_start_s) continue;
    const double h = e.error_ned_m.head<2>().norm();
    std::string why;
    if (!e.valid) why = "no solution";
    else if (e.mode != mode) why = std::string("fell back to ") + aiding::to_string(e.mode);
    else if (e.gnss_measurements < 4) why = fmt::format("{} satellites measured", e.gnss_measurements);
    else if (h > 10.0) why = fmt::format("horizontal error {:.1f} m", h);
    if (!why.empty()) {
      hold.failure = why;
      break;
    }
    hold.until_s = e.t_s;
    hold.max_h_error_m = std::max(hold.max_h_error_m, h);
  }
  return hold;
}

/// Each mode on the aided scenario with a C/N0 ramp: the C/N0 at which it first stops
/// holding (mode_hold).
void run_mode_thresholds(const ThresholdBenchSettings& o) {
  Scenario base = load_scenario(o.aided_scenario, DEEPNAV_SOURCE_DIR);
  if (!o.imu_grade.empty()) base.imu.grade = o.imu_grade;
  if (!o.oscillator.empty()) set_oscillator_preset(base.clock, o.oscillator);
  const Scenario sc = with_ramp(base, o);
  if (!sc.imu.enabled)
    throw InputError("scenario '" + o.aided_scenario + "' has no imu section (the aided modes need one)");
  require_scenario_systems(sc, o.systems, o.aided_scenario);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_threshold_modes");
  SynthesisOptions so;
  so.threads = 0;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);
  BenchReport report("Weak-signal threshold per mode (land circle, C/N0 ramp)",
                     {"mode", "holds_until_s", "threshold_dbhz", "failure", "max_h_error_before_m", "wall_s"});
  for (const char* col : {"holds_until_s", "threshold_dbhz", "max_h_error_before_m", "wall_s"})
    report.set_precision(col, 1);
  for (const auto& name : o.modes) {
    const aiding::NavMode mode = aiding::parse_nav_mode(name);
    AidedRunSettings settings;
    settings.long_integration = o.long_integration;
    settings.systems = o.systems;
    const AidedRunResult r = run_aided_scenario(sc, s, mode, settings);
    const ModeHold hold = mode_hold(r, mode, o.ramp_start_s);
    report.add_row({name, hold.until_s, ramp_cn0_dbhz(o, hold.until_s), hold.failure, hold.max_h_error_m, r.wall_s});
  }
  std::filesystem::remove_all(work);
  report.add_note("ramp", ramp_note(o));
  report.add_note("scenario", source_relative(o.aided_scenario));
  report.add_note("imu_grade", sc.imu.grade);
  report.add_note("oscillator", sc.clock.oscillator);
  report.add_note("ultra_integration", o.long_integration_text);
  report.add_note("coherent_ms", static_cast<long long>(o.long_integration.coherent_ms));
  if (!is_gps_only(o.systems)) report.add_note("systems", systems_list(o.systems));
  report.emit(o.json_path);
}

/// True Doppler and carrier phase per PRN at the truth rate (sat_truth.csv: t_s, prn,
/// code, doppler_hz, carrier phase, ...).
void read_sat_truth(const std::string& path, Series& doppler, Series& phase) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream f(line);
    std::string t, prn, code, dop, ph;
    std::getline(f, t, ',');
    std::getline(f, prn, ',');
    std::getline(f, code, ',');
    std::getline(f, dop, ',');
    std::getline(f, ph, ',');
    doppler[std::stoi(prn)].emplace_back(std::stod(t), std::stod(dop));
    phase[std::stoi(prn)].emplace_back(std::stod(t), std::stod(ph));
  }
}

/// What the scalar run shows of each channel.
struct ChannelFollowing {
  std::map<int, double> last_following_s;  ///< last integration within 5 Hz of the true Doppler
  std::map<int, double> ended_s;           ///< the last integration the channel produced
  Series nco_phase;                        ///< (t, accumulated Doppler phase) while tracking
};

/// The scalar receiver on the ramp, unassisted, with a channel lost staying lost (the
/// threshold is the loss point).
ChannelFollowing follow_channels(const Scenario& sc, const SynthesisSummary& s, Series& truth_doppler) {
  FileSampleSource source(synthesized_source(sc, s));
  aiding::NavigationSessionConfig cfg = scenario_session_config(sc, aiding::NavMode::scalar);
  cfg.navigator.receiver.reacquire_interval_s = 1e9;
  cfg.assisted_iono.reset();  // the scalar sweep has always run unassisted
  cfg.assisted_ephemerides.reset();
  const auto doppler_truth = [&](int prn, double t) {
    const auto& v = truth_doppler[prn];
    const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
    return it == v.end() ? v.back().second : it->second;
  };
  ChannelFollowing f;
  CallbackSink follower({}, [&](const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
    const double t = static_cast<double>(e.first_sample + e.samples) / sc.sample_rate_hz;
    if (ch.state == ChannelState::tracking && std::abs(e.carrier_doppler_hz - doppler_truth(e.prn, t)) < 5.0)
      f.last_following_s[e.prn] = t;
    if (ch.state == ChannelState::tracking) f.nco_phase[e.prn].emplace_back(t, e.carrier_phase_cycles);
    f.ended_s[e.prn] = t;
  });
  aiding::NavigationSession(std::move(cfg), source, std::nullopt, sc.duration_s).run({&follower});
  return f;
}

void run_scalar_threshold(const ThresholdBenchSettings& o) {
  const Scenario sc = with_ramp(load_scenario(o.scenario, DEEPNAV_SOURCE_DIR), o);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_threshold");
  SynthesisOptions so;
  so.threads = 0;
  so.if_only = false;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);
  Series truth_doppler, truth_phase;
  read_sat_truth(s.sat_truth_path, truth_doppler, truth_phase);
  ChannelFollowing f = follow_channels(sc, s, truth_doppler);
  std::filesystem::remove_all(work);

  BenchReport report("Scalar tracking threshold (static, C/N0 ramp)",
                     {"prn", "follows_until_s", "threshold_dbhz", "phase_locked_until_s", "phase_threshold_dbhz",
                      "channel_ended_s", "cn0_at_end_dbhz"});
  for (const char* col : {"follows_until_s", "threshold_dbhz", "phase_locked_until_s", "phase_threshold_dbhz",
                          "channel_ended_s", "cn0_at_end_dbhz"})
    report.set_precision(col, 1);
  std::vector<double> thresholds, phase_thresholds;
  for (const auto& [prn, t] : f.last_following_s) {
    const double cn0 = ramp_cn0_dbhz(o, t);
    thresholds.push_back(cn0);
    const double slip_s = first_cycle_slip_s(f.nco_phase[prn], truth_phase[prn]);
    phase_thresholds.push_back(ramp_cn0_dbhz(o, slip_s));
    report.add_row({static_cast<long long>(prn), t, cn0, slip_s, ramp_cn0_dbhz(o, slip_s), f.ended_s[prn],
                    ramp_cn0_dbhz(o, f.ended_s[prn])});
  }
  std::sort(thresholds.begin(), thresholds.end());
  std::sort(phase_thresholds.begin(), phase_thresholds.end());
  if (!thresholds.empty()) report.add_note("median_threshold_dbhz", thresholds[thresholds.size() / 2]);
  if (!phase_thresholds.empty())
    report.add_note("median_phase_threshold_dbhz", phase_thresholds[phase_thresholds.size() / 2]);
  report.add_note("criteria",
                  "frequency: NCO within 5 Hz of the true Doppler; phase: first cycle slip (the NCO phase "
                  "minus the true carrier phase moves by more than 0.35 cycle within 0.2 s)");
  report.add_note("ramp", ramp_note(o));
  report.add_note("loops", "FLL-assisted PLL 10 Hz (tracking), DLL 0.5 Hz, 10 ms coherent after bit sync");
  report.emit(o.json_path);
}

}  // namespace

std::string default_threshold_scenario() { return source_tree_path("data/scenarios/static_120s.yaml"); }
std::string default_threshold_aided_scenario() { return source_tree_path("data/scenarios/land_circle_aided_90s.yaml"); }

double ramp_cn0_dbhz(const ThresholdBenchSettings& o, double t) {
  if (t <= o.ramp_start_s) return o.start_dbhz;
  return std::max(o.end_dbhz, o.start_dbhz - o.rate_dbps * (t - o.ramp_start_s));
}

void run_threshold_bench(const ThresholdBenchSettings& o) {
  if (!o.modes.empty()) return run_mode_thresholds(o);
  if (!is_gps_only(o.systems))
    throw InputError("--systems: the per-channel sweep follows GPS channels only; name --modes for the per-mode one");
  run_scalar_threshold(o);
}

}  // namespace deepnav::bench
