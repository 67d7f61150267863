// `deepnav bench threshold`: the lowest C/N0 at which the scalar tracking loops keep
// lock. A static scenario whose C/N0 falls slowly (a linear ramp) is synthesized; the
// receiver tracks it and, for each channel, the last moment its carrier frequency
// still follows the true Doppler (within 5 Hz, from the synthesizer's per-satellite
// truth) is read off the ramp: the loop's own lock detector is reported beside it.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "aiding/navigation_session.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "receiver/gnss_receiver.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/long_integration_options.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives
namespace {

struct ThresholdOptions {
  std::string scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/static_120s.yaml";
  double start_dbhz = 40.0;
  double ramp_start_s = 15.0;
  double rate_dbps = 0.25;  ///< C/N0 fall rate
  double end_dbhz = 15.0;
  std::string json_path;
  std::string work_dir;
  std::vector<std::string> modes;  ///< non-empty: the per-mode threshold on the aided scenario
  std::string aided_scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/land_circle_aided_90s.yaml";
  std::string imu_grade;  ///< non-empty: instead of the scenario's
  std::string oscillator;  ///< non-empty: instead of the scenario's
  aiding::LongIntegrationConfig long_integration;
};

/// The scenario with a C/N0 ramp and the length the ramp needs.
Scenario with_ramp(Scenario sc, const ThresholdOptions& o) {
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

/// Each mode on the land circle with a C/N0 ramp: the C/N0 at which it first stops
/// holding a solution within 10 m horizontal in its own mode with at least four
/// satellites' measurements (coasting on the INS alone does not count as holding).
void run_mode_thresholds(const ThresholdOptions& o) {
  Scenario base = load_scenario(o.aided_scenario, DEEPNAV_SOURCE_DIR);
  if (!o.imu_grade.empty()) base.imu.grade = o.imu_grade;
  if (!o.oscillator.empty()) set_oscillator_preset(base.clock, o.oscillator);
  const Scenario sc = with_ramp(base, o);
  if (!sc.imu.enabled) throw UserError("scenario '" + o.aided_scenario + "' has no imu section (the aided modes need one)");
  const std::string work = bench_scratch_dir(o.work_dir, "bench_threshold_modes");
  SynthesisOptions so;
  so.threads = 0;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);
  const auto cn0_at = [&](double t) {
    if (t <= o.ramp_start_s) return o.start_dbhz;
    return std::max(o.end_dbhz, o.start_dbhz - o.rate_dbps * (t - o.ramp_start_s));
  };
  BenchReport report("Weak-signal threshold per mode (land circle, C/N0 ramp)",
                     {"mode", "holds_until_s", "threshold_dbhz", "failure", "max_h_error_before_m", "wall_s"});
  for (const char* col : {"holds_until_s", "threshold_dbhz", "max_h_error_before_m", "wall_s"}) report.set_precision(col, 1);
  for (const auto& name : o.modes) {
    const aiding::NavMode mode = aiding::parse_nav_mode(name);
    AidedRunSettings settings;
    settings.long_integration = o.long_integration;
    const AidedRunResult r = run_aided_scenario(sc, s, mode, settings);
    double holds_until = o.ramp_start_s, max_h = 0.0;
    std::string failure = "held to the end of the ramp";
    for (const auto& e : r.epochs) {
      if (e.t_s <= o.ramp_start_s) continue;
      const double h = e.error_ned_m.head<2>().norm();
      std::string why;
      if (!e.valid) why = "no solution";
      else if (e.mode != mode) why = std::string("fell back to ") + aiding::to_string(e.mode);
      else if (e.gnss_measurements < 4) why = fmt::format("{} satellites measured", e.gnss_measurements);
      else if (h > 10.0) why = fmt::format("horizontal error {:.1f} m", h);
      if (!why.empty()) {
        failure = why;
        break;
      }
      holds_until = e.t_s;
      max_h = std::max(max_h, h);
    }
    report.add_row({name, holds_until, cn0_at(holds_until), failure, max_h, r.wall_s});
  }
  std::filesystem::remove_all(work);
  report.add_note("ramp", fmt::format("{} dB-Hz until {} s, then -{} dB/s to {} dB-Hz", o.start_dbhz, o.ramp_start_s,
                                      o.rate_dbps, o.end_dbhz));
  report.add_note("scenario", source_relative(o.aided_scenario));
  report.add_note("imu_grade", sc.imu.grade);
  report.add_note("oscillator", sc.clock.oscillator);
  report.add_note("ultra_integration", describe(o.long_integration));
  report.add_note("coherent_ms", static_cast<long long>(o.long_integration.coherent_ms));
  report.emit(o.json_path);
}

/// Linear interpolation in a time-sorted series.
double interpolate(const std::vector<std::pair<double, double>>& v, double t) {
  const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
  if (it == v.begin()) return v.front().second;
  if (it == v.end()) return v.back().second;
  const auto& [t1, y1] = *it;
  const auto& [t0, y0] = *std::prev(it);
  return y0 + (y1 - y0) * (t - t0) / (t1 - t0);
}

/// Time of the first cycle slip of a channel: its NCO phase minus the true carrier phase
/// (either sign convention; the one that stays constant is used) moves by more than 0.35
/// cycle within 0.2 s. The end of tracking when there is none.
double first_cycle_slip_s(const std::vector<std::pair<double, double>>& nco,
                          const std::vector<std::pair<double, double>>& truth) {
  if (nco.size() < 40 || truth.size() < 2) return nco.empty() ? 0.0 : nco.back().first;
  std::vector<double> plus(nco.size()), minus(nco.size());
  for (std::size_t k = 0; k < nco.size(); ++k) {
    const double p = interpolate(truth, nco[k].first);
    plus[k] = nco[k].second + p;
    minus[k] = nco[k].second - p;
  }
  const auto spread = [](const std::vector<double>& d) { return std::abs(d[20] - d[0]) + std::abs(d[39] - d[20]); };
  const std::vector<double>& d = spread(plus) < spread(minus) ? plus : minus;
  std::size_t back = 0;
  for (std::size_t k = 1; k < d.size(); ++k) {
    while (nco[k].first - nco[back].first > 0.2) ++back;
    if (std::abs(d[k] - d[back]) > 0.35) return nco[k].first;
  }
  return nco.back().first;
}

void run_threshold(const ThresholdOptions& o) {
  if (!o.modes.empty()) return run_mode_thresholds(o);
  const Scenario sc = with_ramp(load_scenario(o.scenario, DEEPNAV_SOURCE_DIR), o);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_threshold");
  SynthesisOptions so;
  so.threads = 0;
  so.if_only = false;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);

  FileSampleSource source(synthesized_source(sc, s));
  aiding::NavigationSessionConfig cfg = scenario_session_config(sc, aiding::NavMode::scalar);
  cfg.navigator.receiver.reacquire_interval_s = 1e9;  // a channel lost stays lost: the threshold is the loss point
  cfg.assisted_iono.reset();  // the scalar sweep has always run unassisted
  cfg.assisted_ephemerides.reset();
  // True Doppler per PRN at the truth rate (sat_truth.csv: t_s, prn, code, doppler_hz, ...).
  std::map<int, std::vector<std::pair<double, double>>> truth_doppler, truth_phase;
  {
    std::ifstream in(s.sat_truth_path);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::stringstream f(line);
      std::string t, prn, code, dop, phase;
      std::getline(f, t, ',');
      std::getline(f, prn, ',');
      std::getline(f, code, ',');
      std::getline(f, dop, ',');
      std::getline(f, phase, ',');
      truth_doppler[std::stoi(prn)].emplace_back(std::stod(t), std::stod(dop));
      truth_phase[std::stoi(prn)].emplace_back(std::stod(t), std::stod(phase));
    }
  }
  const auto doppler_truth = [&](int prn, double t) {
    const auto& v = truth_doppler[prn];
    const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
    return it == v.end() ? v.back().second : it->second;
  };
  std::map<int, double> last_following_s, declared_lost_s;
  std::map<int, std::vector<std::pair<double, double>>> nco_phase;  // (t, accumulated Doppler phase) while tracking
  CallbackSink follower({}, [&](const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
    const double t = static_cast<double>(e.first_sample + e.samples) / sc.sample_rate_hz;
    if (ch.state == ChannelState::tracking && std::abs(e.carrier_doppler_hz - doppler_truth(e.prn, t)) < 5.0)
      last_following_s[e.prn] = t;
    if (ch.state == ChannelState::tracking) nco_phase[e.prn].emplace_back(t, e.carrier_phase_cycles);
    declared_lost_s[e.prn] = t;  // the last epoch the channel produced
  });
  aiding::NavigationSession(std::move(cfg), source, std::nullopt, sc.duration_s).run({&follower});
  std::filesystem::remove_all(work);

  const auto cn0_at = [&](double t) {
    if (t <= o.ramp_start_s) return o.start_dbhz;
    return std::max(o.end_dbhz, o.start_dbhz - o.rate_dbps * (t - o.ramp_start_s));
  };
  BenchReport report("Scalar tracking threshold (static, C/N0 ramp)",
                     {"prn", "follows_until_s", "threshold_dbhz", "phase_locked_until_s", "phase_threshold_dbhz",
                      "channel_ended_s", "cn0_at_end_dbhz"});
  for (const char* col : {"follows_until_s", "threshold_dbhz", "phase_locked_until_s", "phase_threshold_dbhz",
                          "channel_ended_s", "cn0_at_end_dbhz"})
    report.set_precision(col, 1);
  std::vector<double> thresholds, phase_thresholds;
  for (const auto& [prn, t] : last_following_s) {
    const double cn0 = cn0_at(t);
    thresholds.push_back(cn0);
    const double slip_s = first_cycle_slip_s(nco_phase[prn], truth_phase[prn]);
    phase_thresholds.push_back(cn0_at(slip_s));
    report.add_row({static_cast<long long>(prn), t, cn0, slip_s, cn0_at(slip_s), declared_lost_s[prn],
                    cn0_at(declared_lost_s[prn])});
  }
  std::sort(thresholds.begin(), thresholds.end());
  std::sort(phase_thresholds.begin(), phase_thresholds.end());
  if (!thresholds.empty()) report.add_note("median_threshold_dbhz", thresholds[thresholds.size() / 2]);
  if (!phase_thresholds.empty()) report.add_note("median_phase_threshold_dbhz", phase_thresholds[phase_thresholds.size() / 2]);
  report.add_note("criteria", "frequency: NCO within 5 Hz of the true Doppler; phase: first cycle slip (the NCO phase "
                              "minus the true carrier phase moves by more than 0.35 cycle within 0.2 s)");
  report.add_note("ramp", fmt::format("{} dB-Hz until {} s, then -{} dB/s to {} dB-Hz", o.start_dbhz, o.ramp_start_s,
                                      o.rate_dbps, o.end_dbhz));
  report.add_note("loops", "FLL-assisted PLL 10 Hz (tracking), DLL 0.5 Hz, 10 ms coherent after bit sync");
  report.emit(o.json_path);
}

}  // namespace

void add_bench_threshold_command(CommandParents& parents) {
  auto o = std::make_shared<ThresholdOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("threshold", "Lowest C/N0 at which the scalar loops keep lock (C/N0 ramp)");
  cmd->add_option("--scenario", o->scenario, "Base scenario (static)")->capture_default_str();
  cmd->add_option("--start", o->start_dbhz, "C/N0 before the ramp (dB-Hz)")->capture_default_str();
  cmd->add_option("--ramp-start", o->ramp_start_s, "Ramp start (s)")->capture_default_str();
  cmd->add_option("--rate", o->rate_dbps, "C/N0 fall rate (dB/s)")->capture_default_str();
  cmd->add_option("--end", o->end_dbhz, "Lowest C/N0 (dB-Hz)")->capture_default_str();
  cmd->add_option("--modes", o->modes,
                  "Instead: each of these modes (scalar,loose,tight,ultra) on the land circle with an IMU; the C/N0 at "
                  "which it stops holding a 10 m solution from satellite measurements")
      ->delimiter(',');
  cmd->add_option("--aided-scenario", o->aided_scenario, "Scenario for --modes (needs an imu section)")->capture_default_str();
  cmd->add_option("--imu-grade", o->imu_grade, "With --modes: this IMU grade instead of the scenario's (e.g. consumer)");
  cmd->add_option("--oscillator", o->oscillator, "With --modes: this receiver oscillator instead of the scenario's (ideal, tcxo, ocxo)")
      ->check(CLI::IsMember({"ideal", "tcxo", "ocxo"}));
  add_long_integration_options(*cmd, o->long_integration);
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF file is written");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->callback([o] { run_threshold(*o); });
}

}  // namespace deepnav::cli
