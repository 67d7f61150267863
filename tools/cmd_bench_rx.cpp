// `deepnav bench rx`: how fast the receiver runs. A 12-satellite scenario (4.092 Msps
// ibyte) is synthesized once; the receiver then processes it with 8 and 12 channels, on
// one thread and on every core, and in ultra-tight mode (12 channels, 100 Hz filter). The
// real-time factor is signal seconds per wall second. The correlator alone is timed on
// 12 channels' 1 ms spans for every kernel this CPU has.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>
#include <thread>

#include "aiding/aided_receiver.hpp"
#include "ins/imu_file.hpp"
#include "receiver/correlator.hpp"
#include "receiver/file_sample_source.hpp"
#include "receiver/scalar_receiver.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/aided_scenario_run.hpp"
#include "tools/bench_report.hpp"
#include "tools/command_registry.hpp"

namespace deepnav::cli {
namespace {

struct RxBenchOptions {
  std::string scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/rx_speed_12sat.yaml";
  double duration_s = 60.0;
  int repeats = 3;
  std::string work_dir, json_path;
};

struct RunFigures {
  double wall_s = 0.0;
  int max_tracking = 0;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

RunFigures run_scalar(const Scenario& sc, const SynthesisSummary& s, int channels, unsigned threads) {
  FileSampleSource source(synthesized_source(sc, s));
  ReceiverConfig rc;
  rc.channels = channels;
  rc.threads = threads;
  rc.reference_week = sc.start_time.week;
  ScalarReceiver rx(rc, source);
  rx.set_assisted_ephemerides(read_rinex_nav(sc.nav_file));
  RunFigures f;
  const auto t0 = std::chrono::steady_clock::now();
  rx.run([&](const ReceiverEpoch& ep) { f.max_tracking = std::max(f.max_tracking, ep.channels_tracking); });
  f.wall_s = seconds_since(t0);
  return f;
}

RunFigures run_ultra(const Scenario& sc, const SynthesisSummary& s) {
  FileSampleSource source(synthesized_source(sc, s));
  aiding::AidedReceiverConfig cfg;
  cfg.mode = aiding::NavMode::ultra;
  cfg.receiver.reference_week = sc.start_time.week;
  cfg.imu = load_imu_grade(sc.imu.grades_file, sc.imu.grade).model;
  aiding::AidedReceiver rx(cfg, source, read_imu_csv(s.imu_path), sc.duration_s);
  rx.receiver().set_assisted_ephemerides(read_rinex_nav(sc.nav_file));
  RunFigures f;
  const auto t0 = std::chrono::steady_clock::now();
  rx.run([&](const aiding::AidedEpoch& a) {
    if (a.mode == aiding::NavMode::ultra) f.max_tracking = std::max(f.max_tracking, a.steered_channels);
  });
  f.wall_s = seconds_since(t0);
  return f;
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

const char* kernel_name(CorrelatorKernel k) {
  switch (k) {
    case CorrelatorKernel::avx512: return "avx512";
    case CorrelatorKernel::avx2: return "avx2";
    case CorrelatorKernel::portable: return "portable";
  }
  return "?";
}

/// Channel-samples per second of one kernel: 12 channels, each its own PRN, Doppler and
/// code phase, over the same 1 ms of 4.092 Msps noise, repeated for about a second.
double correlator_throughput(CorrelatorKernel kernel) {
  const int n = 4092;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> level(-7, 7);
  std::vector<Sample> samples(static_cast<std::size_t>(n));
  for (auto& x : samples) x = Sample(static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng)));
  // As the receiver calls it: the block's magnitude scan and planar copy made once, outside the timing.
  std::vector<std::int16_t> i(samples.size()), q(samples.size());
  deinterleave(samples.data(), n, i.data(), q.data());
  const CorrelatorInput input{samples.data(), i.data(), q.data()};
  std::vector<CorrelatorSpan> spans(12);
  for (int c = 0; c < 12; ++c) {
    spans[static_cast<std::size_t>(c)].magnitude_bits = sample_magnitude_bits(samples.data(), n);
    spans[static_cast<std::size_t>(c)].carrier_step_cycles = (1000.0 * c - 5000.0) / 4.092e6;
    spans[static_cast<std::size_t>(c)].code_phase_chips = 85.3 * c;
    spans[static_cast<std::size_t>(c)].code_step_chips = gps::kCodeRate_cps / 4.092e6 * (1.0 + 1e-6 * c);
  }
  double sink = 0.0;
  long long calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (seconds_since(t0) < 1.0) {
    for (int c = 0; c < 12; ++c) {
      const CorrelatorSums r = correlate(kernel, input, n, spans[static_cast<std::size_t>(c)],
                                         ca_code_chips(c + 1), ca_code_chips(32));
      sink += r.prompt.real();
      ++calls;
    }
  }
  const double wall = seconds_since(t0);
  if (sink == 1e300) fmt::print("{}", sink);  // keeps the work observable
  return static_cast<double>(calls) * n / wall;
}

void run_rx_bench(const RxBenchOptions& o) {
  Scenario sc = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  sc.duration_s = o.duration_s;
  if (!sc.imu.enabled) throw UserError("scenario '" + o.scenario + "' needs an imu section (ultra-tight case)");
  validate_scenario(sc);
  const std::string work =
      o.work_dir.empty() ? (std::filesystem::temp_directory_path() / "deepnav_bench_rx").string() : o.work_dir;
  SynthesisOptions so;
  so.threads = 0;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());

  BenchReport report("Receiver speed (4.092 Msps ibyte)",
                     {"case", "channels", "threads", "tracking", "signal_s", "wall_s", "realtime_factor",
                      "channel_samples_per_s"});
  report.set_precision("signal_s", 1);
  report.set_precision("wall_s", 2);
  report.set_precision("realtime_factor", 1);
  report.set_precision("channel_samples_per_s", 3);
  const auto add = [&](const std::string& name, int channels, unsigned threads, const RunFigures& f) {
    const double rt = sc.duration_s / f.wall_s;
    report.add_row({name, static_cast<long long>(channels), static_cast<long long>(threads),
                    static_cast<long long>(f.max_tracking), sc.duration_s, f.wall_s, rt,
                    rt * sc.sample_rate_hz * channels});
  };
  for (int channels : {8, 12}) {
    add("scalar", channels, 1, median_run(o.repeats, [&] { return run_scalar(sc, s, channels, 1); }));
    if (cores > 1) add("scalar", channels, cores, median_run(o.repeats, [&] { return run_scalar(sc, s, channels, cores); }));
  }
  add("ultra-tight", 12, 1, median_run(o.repeats, [&] { return run_ultra(sc, s); }));
  for (CorrelatorKernel k : available_correlator_kernels()) {
    const double rate = correlator_throughput(k);
    report.add_row({std::string("correlator ") + kernel_name(k), 12LL, 1LL, 0LL, 0.0, 0.0, 0.0, rate});
  }
  std::filesystem::remove_all(work);
  report.add_note("scenario", source_relative(o.scenario));
  report.add_note("repeats", std::to_string(o.repeats) + " runs per receiver row, the median shown");
  report.add_note("notes", "receiver rows: whole receiver (acquisition, tracking, navigation data, PVT; assisted "
                           "ephemerides); channel_samples_per_s = realtime_factor x fs x channels. Correlator rows: "
                           "E/P/L + noise taps over 1 ms spans, one core, input prepared once per block as in the receiver "
                           "(magnitude scan; planar copy for avx512).");
  report.emit(o.json_path);
}

const bool registered = register_command([](CommandParents& parents) {
  auto o = std::make_shared<RxBenchOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("rx", "Receiver real-time factor (8/12 channels, 1 thread/all cores, ultra) and correlator throughput");
  cmd->add_option("--scenario", o->scenario, "Scenario with 12 satellites and an imu section")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Signal length (s)")->capture_default_str();
  cmd->add_option("--repeats", o->repeats, "Runs per receiver case; the median is reported")
      ->check(CLI::Range(1, 99))
      ->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF file is written");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->callback([o] { run_rx_bench(*o); });
});

}  // namespace
}  // namespace deepnav::cli
