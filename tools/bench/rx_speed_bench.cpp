#include "tools/bench/rx_speed_bench.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "aiding/navigation_session.hpp"
#include "ins/imu_file.hpp"
#include "ins/input_error.hpp"
#include "receiver/gnss_receiver.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "receiver/tracking/correlator.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/correlator_throughput.hpp"
#include "tools/bench/cpu_description.hpp"
#include "tools/bench/process_usage.hpp"

namespace deepnav::bench {
namespace {

struct RunFigures {
  double wall_s = 0.0;
  double cpu_s = 0.0;  ///< CPU time of the process (all threads) over the run
  int max_tracking = 0;
};

/// One run of the scenario through the pipeline every run uses; `tracking` reads an
/// epoch's count of channels doing work (tracking, or steered and measuring).
template <typename Tracking>
RunFigures run_session(const Scenario& sc, const SynthesisSummary& s, aiding::NavigationSessionConfig cfg,
                       Tracking tracking) {
  FileSampleSource source(synthesized_source(sc, s));
  std::optional<ImuLog> imu = scenario_imu_log(s, cfg.navigator.mode);
  aiding::NavigationSession session(std::move(cfg), source, std::move(imu), sc.duration_s);
  RunFigures f;
  CallbackSink counter([&](const NavigationEpoch& e) { f.max_tracking = std::max(f.max_tracking, tracking(e)); });
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = process_cpu_s();
  session.run({&counter});
  f.wall_s = seconds_since(t0);
  f.cpu_s = process_cpu_s() - c0;
  return f;
}

RunFigures run_scalar(const Scenario& sc, const SynthesisSummary& s, int channels, unsigned threads,
                      const std::vector<GnssSystem>& systems = {GnssSystem::gps}) {
  aiding::NavigationSessionConfig cfg = scenario_session_config(sc, aiding::NavMode::scalar);
  cfg.navigator.receiver.channels = channels;
  cfg.navigator.receiver.threads = threads;
  cfg.navigator.receiver.systems = systems;
  return run_session(sc, s, std::move(cfg), [](const NavigationEpoch& e) { return e.receiver.channels_tracking; });
}

RunFigures run_ultra(const Scenario& sc, const SynthesisSummary& s) {
  return run_session(sc, s, scenario_session_config(sc, aiding::NavMode::ultra),
                     [](const NavigationEpoch& e) { return e.mode == "ultra" ? e.gnss_measurements : 0; });
}

/// The run with the median wall time of `repeats` (a shared machine's noise, page cache
/// warm-up and frequency changes move single runs by 10-20 %).
template <typename Run>
RunFigures median_run(int repeats, Run run) {
  std::vector<RunFigures> runs;
  for (int r = 0; r < repeats; ++r) runs.push_back(run());
  std::sort(runs.begin(), runs.end(), [](const RunFigures& a, const RunFigures& b) { return a.wall_s < b.wall_s; });
  return runs[runs.size() / 2];
}

/// Uses the kernel the settings name (when they name one); returns the kernel in use.
CorrelatorKernel choose_kernel(const std::string& name) {
  if (!name.empty()) {
    try {
      use_correlator_kernel(correlator_kernel_named(name));
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--kernel: ") + e.what());
    }
  }
  return best_correlator_kernel();  // also reads DEEPNAV_CORRELATOR_KERNEL
}

BenchReport speed_table() {
  BenchReport report("Receiver speed (ibyte: 4.092 Msps GPS scenario, 4 Msps GPS+Galileo scenario)",
                     {"case", "channels", "threads", "tracking", "signal_s", "wall_s", "cpu_s", "realtime_factor",
                      "realtime_factor_cpu", "channel_samples_per_s", "channel_samples_per_cpu_s"});
  report.set_precision("signal_s", 1);
  report.set_precision("wall_s", 2);
  report.set_precision("cpu_s", 2);
  report.set_precision("realtime_factor", 1);
  report.set_precision("realtime_factor_cpu", 1);
  report.set_precision("channel_samples_per_s", 3);
  report.set_precision("channel_samples_per_cpu_s", 3);
  return report;
}

/// A receiver run's row: its real-time factors over the scenario's signal.
void add_receiver_row(BenchReport& report, const Scenario& sc, const std::string& name, int channels, unsigned threads,
                      const RunFigures& f) {
  const double rt = sc.duration_s / f.wall_s, rt_cpu = sc.duration_s / f.cpu_s;
  report.add_row({name, static_cast<long long>(channels), static_cast<long long>(threads),
                  static_cast<long long>(f.max_tracking), sc.duration_s, f.wall_s, f.cpu_s, rt, rt_cpu,
                  rt * sc.sample_rate_hz * channels, rt_cpu * sc.sample_rate_hz * channels});
}

/// One row per kernel this CPU has, with and without the noise tap; returns the kernels' names.
std::vector<std::string> add_correlator_rows(BenchReport& report) {
  std::vector<std::string> kernels;
  for (CorrelatorKernel k : available_correlator_kernels()) {
    kernels.emplace_back(correlator_kernel_name(k));
    for (bool noise_tap : {true, false}) {
      const CorrelatorThroughput t = correlator_throughput(k, noise_tap);
      report.add_row({std::string("correlator ") + correlator_kernel_name(k) + (noise_tap ? "" : " E/P/L"), 12LL, 1LL,
                      0LL, 0.0, t.wall_s, t.cpu_s, 0.0, 0.0, t.channel_samples / t.wall_s,
                      t.channel_samples / t.cpu_s});
    }
  }
  return kernels;
}

/// The E1 correlator per kernel this CPU has (with and without the noise pass), and the
/// double-precision reference the Galileo channels ran before the fixed-point kernels.
void add_e1_correlator_rows(BenchReport& report) {
  const auto row = [&](const std::string& name, const CorrelatorThroughput& t) {
    report.add_row({name, 8LL, 1LL, 0LL, 0.0, t.wall_s, t.cpu_s, 0.0, 0.0, t.channel_samples / t.wall_s,
                    t.channel_samples / t.cpu_s});
  };
  row("E1 correlator reference (double)", e1_correlator_throughput(std::nullopt, true));
  for (CorrelatorKernel k : available_correlator_kernels()) {
    row(std::string("E1 correlator ") + correlator_kernel_name(k), e1_correlator_throughput(k, true));
    row(std::string("E1 correlator ") + correlator_kernel_name(k) + " no noise", e1_correlator_throughput(k, false));
  }
}

}  // namespace

std::string default_rx_speed_scenario() { return source_tree_path("data/scenarios/rx_speed_12sat.yaml"); }
std::string default_rx_speed_galileo_scenario() {
  return source_tree_path("data/scenarios/static_gps_galileo_60s.yaml");
}

namespace {

/// The mixed scenario's rows: GPS alone and GPS+Galileo on the same samples.
void add_galileo_rows(const RxSpeedSettings& o, const std::string& work, unsigned cores, BenchReport& report) {
  Scenario sc = load_scenario(o.galileo_scenario, DEEPNAV_SOURCE_DIR);
  sc.duration_s = o.duration_s;
  validate_scenario(sc);
  if (!includes_system(sc.systems, GnssSystem::galileo))
    throw InputError("scenario '" + o.galileo_scenario + "' has no Galileo satellites (systems: [gps, galileo])");
  SynthesisOptions so;
  so.threads = 0;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work + "/galileo", so);
  const int gps_channels = 12, galileo_channels = ReceiverConfig{}.galileo.channels;
  const std::vector<GnssSystem> both{GnssSystem::gps, GnssSystem::galileo};
  std::vector<unsigned> thread_counts{1};
  if (cores > 1) thread_counts.push_back(cores);
  for (unsigned threads : thread_counts) {
    add_receiver_row(report, sc, "scalar GPS, mixed IF", gps_channels, threads,
                     median_run(o.repeats, [&] { return run_scalar(sc, s, gps_channels, threads); }));
    add_receiver_row(report, sc, "scalar GPS+Galileo", gps_channels + galileo_channels, threads,
                     median_run(o.repeats, [&] { return run_scalar(sc, s, gps_channels, threads, both); }));
  }
  report.add_note("galileo_scenario", source_relative(o.galileo_scenario));
  add_e1_correlator_rows(report);
}

}  // namespace

void run_rx_speed_bench(const RxSpeedSettings& o) {
  const CorrelatorKernel in_use = choose_kernel(o.kernel);
  Scenario sc = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  sc.duration_s = o.duration_s;
  if (!sc.imu.enabled) throw InputError("scenario '" + o.scenario + "' needs an imu section (ultra-tight case)");
  validate_scenario(sc);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_rx");
  SynthesisOptions so;
  so.threads = 0;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());

  BenchReport report = speed_table();
  for (int channels : {8, 12}) {
    add_receiver_row(report, sc, "scalar", channels, 1,
                     median_run(o.repeats, [&] { return run_scalar(sc, s, channels, 1); }));
    if (cores > 1)
      add_receiver_row(report, sc, "scalar", channels, cores,
                       median_run(o.repeats, [&] { return run_scalar(sc, s, channels, cores); }));
  }
  add_receiver_row(report, sc, "ultra-tight", 12, 1, median_run(o.repeats, [&] { return run_ultra(sc, s); }));
  if (includes_system(o.systems, GnssSystem::galileo)) add_galileo_rows(o, work, cores, report);
  const std::vector<std::string> kernels = add_correlator_rows(report);
  std::filesystem::remove_all(work);
  report.add_note("cpu", cpu_model());
  report.add_note("instruction_sets", instruction_sets());
  report.add_note("correlator_kernels", kernels);
  report.add_note("kernel_in_use",
                  std::string(correlator_kernel_name(in_use)) +
                      (in_use == fastest_correlator_kernel()
                           ? ""
                           : " (chosen; the CPU's fastest is " +
                                 std::string(correlator_kernel_name(fastest_correlator_kernel())) + ")"));
  report.add_note("scenario", source_relative(o.scenario));
  report.add_note("repeats", std::to_string(o.repeats) + " runs per receiver row, the median shown");
  report.add_note(
      "notes",
      "receiver rows: whole receiver (acquisition, tracking, navigation data, PVT; assisted "
      "ephemerides); channel_samples_per_s = realtime_factor x fs x channels; the *_cpu columns "
      "use the process's CPU time instead of wall time (on a shared machine the one-thread figures "
      "are closer to an idle machine's). Correlator rows: "
      "E/P/L + noise taps (\"E/P/L\": without the noise tap, as the receiver runs most integrations) over 1 ms "
      "spans, one core, input prepared once per block as in the receiver (magnitude scan; planar "
      "copy for avx512). E1 correlator rows (with --systems galileo): 4 ms spans at 4 Msps, five "
      "pilot taps and the data prompt, with the noise pass (\"no noise\": without it, as the channels run "
      "every period but an integration's first); \"reference (double)\": the double-precision sums.");
  report.emit(o.json_path);
}

}  // namespace deepnav::bench
