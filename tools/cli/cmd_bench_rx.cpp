// `deepnav bench rx`: how fast the receiver runs. A 12-satellite scenario (4.092 Msps
// ibyte) is synthesized once; the receiver then processes it with 8 and 12 channels, on
// one thread and on every core, and in ultra-tight mode (12 channels, 100 Hz filter). The
// real-time factor is signal seconds per wall second. The correlator alone is timed on
// 12 channels' 1 ms spans for every kernel this CPU has. The report names the CPU, the
// instruction sets found and the kernel the receiver used (--kernel or the environment
// variable DEEPNAV_CORRELATOR_KERNEL picks another, e.g. avx2 to measure as on a CPU
// without AVX-512).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "aiding/navigation_session.hpp"
#include "ins/imu_file.hpp"
#include "receiver/tracking/correlator.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "receiver/gnss_receiver.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/aided_scenario_run.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/process_usage.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives
namespace {

struct RxBenchOptions {
  std::string scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/rx_speed_12sat.yaml";
  double duration_s = 60.0;
  int repeats = 3;
  std::string work_dir, json_path;
  std::string kernel;  ///< correlator kernel for the receiver runs; empty: the default
};

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

RunFigures run_scalar(const Scenario& sc, const SynthesisSummary& s, int channels, unsigned threads) {
  aiding::NavigationSessionConfig cfg = scenario_session_config(sc, aiding::NavMode::scalar);
  cfg.navigator.receiver.channels = channels;
  cfg.navigator.receiver.threads = threads;
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

/// The CPU's model name as the kernel reports it ("unknown" where it does not).
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    for (const char* key : {"model name", "Model"}) {
      if (line.rfind(key, 0) == 0) {
        if (const auto colon = line.find(':'); colon != std::string::npos) {
          const auto first = line.find_first_not_of(" \t", colon + 1);
          if (first != std::string::npos) return line.substr(first);
        }
      }
    }
  }
  return "unknown";
}

/// The SIMD instruction sets the correlator kernels care about that this CPU has.
std::vector<std::string> instruction_sets() {
  std::vector<std::string> found;
#if defined(__x86_64__)
  __builtin_cpu_init();
  const auto add = [&](bool has, const char* name) {
    if (has) found.emplace_back(name);
  };
  add(__builtin_cpu_supports("sse4.2"), "sse4.2");
  add(__builtin_cpu_supports("avx"), "avx");
  add(__builtin_cpu_supports("avx2"), "avx2");
  add(__builtin_cpu_supports("fma"), "fma");
  add(__builtin_cpu_supports("avx512f"), "avx512f");
  add(__builtin_cpu_supports("avx512bw"), "avx512bw");
  add(__builtin_cpu_supports("avx512vl"), "avx512vl");
  add(__builtin_cpu_supports("avx512vnni"), "avx512vnni");
#elif defined(__aarch64__)
  found.emplace_back("neon");
#endif
  return found;
}

struct Throughput {
  double wall_s, cpu_s, channel_samples;
};

/// One kernel: 12 channels, each its own PRN, Doppler and code phase, over the same 1 ms of
/// 4.092 Msps noise, repeated for about a second.
Throughput correlator_throughput(CorrelatorKernel kernel, bool noise_tap) {
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
    spans[static_cast<std::size_t>(c)].noise_tap = noise_tap;
  }
  double sink = 0.0;
  long long calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_s();
  while (seconds_since(t0) < 1.0) {
    for (int c = 0; c < 12; ++c) {
      const CorrelatorSums r = correlate(kernel, input, n, spans[static_cast<std::size_t>(c)],
                                         ca_code_chips(c + 1), ca_code_chips(32));
      sink += r.prompt.real();
      ++calls;
    }
  }
  const double wall = seconds_since(t0), cpu = thread_cpu_s() - c0;
  if (sink == 1e300) fmt::print("{}", sink);  // keeps the work observable
  return {wall, cpu, static_cast<double>(calls) * n};
}

void run_rx_bench(const RxBenchOptions& o) {
  if (!o.kernel.empty()) {
    try {
      use_correlator_kernel(correlator_kernel_named(o.kernel));
    } catch (const std::invalid_argument& e) {
      throw UserError(std::string("--kernel: ") + e.what());
    }
  }
  const CorrelatorKernel in_use = best_correlator_kernel();  // also reads DEEPNAV_CORRELATOR_KERNEL
  Scenario sc = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  sc.duration_s = o.duration_s;
  if (!sc.imu.enabled) throw UserError("scenario '" + o.scenario + "' needs an imu section (ultra-tight case)");
  validate_scenario(sc);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_rx");
  SynthesisOptions so;
  so.threads = 0;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());

  BenchReport report("Receiver speed (4.092 Msps ibyte)",
                     {"case", "channels", "threads", "tracking", "signal_s", "wall_s", "cpu_s", "realtime_factor",
                      "realtime_factor_cpu", "channel_samples_per_s", "channel_samples_per_cpu_s"});
  report.set_precision("signal_s", 1);
  report.set_precision("wall_s", 2);
  report.set_precision("cpu_s", 2);
  report.set_precision("realtime_factor", 1);
  report.set_precision("realtime_factor_cpu", 1);
  report.set_precision("channel_samples_per_s", 3);
  report.set_precision("channel_samples_per_cpu_s", 3);
  const auto add = [&](const std::string& name, int channels, unsigned threads, const RunFigures& f) {
    const double rt = sc.duration_s / f.wall_s, rt_cpu = sc.duration_s / f.cpu_s;
    report.add_row({name, static_cast<long long>(channels), static_cast<long long>(threads),
                    static_cast<long long>(f.max_tracking), sc.duration_s, f.wall_s, f.cpu_s, rt, rt_cpu,
                    rt * sc.sample_rate_hz * channels, rt_cpu * sc.sample_rate_hz * channels});
  };
  for (int channels : {8, 12}) {
    add("scalar", channels, 1, median_run(o.repeats, [&] { return run_scalar(sc, s, channels, 1); }));
    if (cores > 1) add("scalar", channels, cores, median_run(o.repeats, [&] { return run_scalar(sc, s, channels, cores); }));
  }
  add("ultra-tight", 12, 1, median_run(o.repeats, [&] { return run_ultra(sc, s); }));
  std::vector<std::string> kernels;
  for (CorrelatorKernel k : available_correlator_kernels()) {
    kernels.emplace_back(correlator_kernel_name(k));
    for (bool noise_tap : {true, false}) {
      const Throughput t = correlator_throughput(k, noise_tap);
      report.add_row({std::string("correlator ") + correlator_kernel_name(k) + (noise_tap ? "" : " E/P/L"), 12LL, 1LL,
                      0LL, 0.0, t.wall_s, t.cpu_s, 0.0, 0.0, t.channel_samples / t.wall_s, t.channel_samples / t.cpu_s});
    }
  }
  std::filesystem::remove_all(work);
  report.add_note("cpu", cpu_model());
  report.add_note("instruction_sets", instruction_sets());
  report.add_note("correlator_kernels", kernels);
  report.add_note("kernel_in_use", std::string(correlator_kernel_name(in_use)) +
                                       (in_use == fastest_correlator_kernel() ? "" : " (chosen; the CPU's fastest is " +
                                                                                     std::string(correlator_kernel_name(fastest_correlator_kernel())) + ")"));
  report.add_note("scenario", source_relative(o.scenario));
  report.add_note("repeats", std::to_string(o.repeats) + " runs per receiver row, the median shown");
  report.add_note("notes", "receiver rows: whole receiver (acquisition, tracking, navigation data, PVT; assisted "
                           "ephemerides); channel_samples_per_s = realtime_factor x fs x channels; the *_cpu columns "
                           "use the process's CPU time instead of wall time (on a shared machine the one-thread figures "
                           "are closer to an idle machine's). Correlator rows: "
                           "E/P/L + noise taps (\"E/P/L\": without the noise tap, as the receiver runs most integrations) over 1 ms "
                           "spans, one core, input prepared once per block as in the receiver (magnitude scan; planar "
                           "copy for avx512).");
  report.emit(o.json_path);
}

}  // namespace

void add_bench_rx_command(CommandParents& parents) {
  auto o = std::make_shared<RxBenchOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("rx", "Receiver real-time factor (8/12 channels, 1 thread/all cores, ultra) and correlator throughput");
  cmd->add_option("--scenario", o->scenario, "Scenario with 12 satellites and an imu section")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Signal length (s)")->capture_default_str();
  cmd->add_option("--repeats", o->repeats, "Runs per receiver case; the median is reported")
      ->check(CLI::Range(1, 99))
      ->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF file is written");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->add_option("--kernel", o->kernel,
                  "Correlator kernel for the receiver runs (portable, avx2, avx512, neon; default: the CPU's fastest, or "
                  "DEEPNAV_CORRELATOR_KERNEL)");
  cmd->callback([o] { run_rx_bench(*o); });
}

}  // namespace deepnav::cli
