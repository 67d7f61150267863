// `deepnav bench sim`: synthesis speed (seconds of signal per second of wall time)
// on one core and on all cores, and the peak resident memory of the process.
#include <fmt/format.h>

#include <filesystem>
#include <thread>

#include "signals/sim/if_synthesizer.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/process_usage.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives
namespace {

struct BenchSimOptions {
  std::string scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/default.yaml";
  double duration_s = 10.0;
  int satellites = 10;
  std::string format = "ibyte";
  int adc_bits = 2;
  std::string work_dir;
  std::string json_path;
};

void run_bench(const BenchSimOptions& o) {
  Scenario sc = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  sc.duration_s = o.duration_s;
  sc.max_satellites = o.satellites;
  sc.elevation_mask_rad = 0.0;
  sc.format = parse_sample_format(o.format);
  sc.adc.bits = o.adc_bits;
  validate_scenario(sc);
  const NavData nav = read_rinex_nav(sc.nav_file);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_sim");

  BenchReport report("IF synthesis speed", {"threads", "satellites", "signal_s", "wall_s", "x_real_time",
                                            "ns_per_sample", "peak_rss_mib"});
  report.set_precision("x_real_time", 1);
  report.set_precision("ns_per_sample", 2);
  report.set_precision("peak_rss_mib", 1);
  const unsigned all = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned threads : {1u, all}) {
    if (threads == all && all == 1 && report.to_json()["rows"].size() == 1) break;
    IfSynthesizer synth(sc, nav);
    SynthesisOptions options;
    options.threads = threads;
    options.if_only = true;
    const SynthesisSummary s = synth.run(work, options);
    std::filesystem::remove_all(work);
    report.add_row({static_cast<long long>(threads), static_cast<long long>(s.satellites.size()), s.duration_s,
                    s.wall_s, s.duration_s / s.wall_s, 1e9 * s.wall_s / static_cast<double>(s.samples),
                    peak_rss_mib()});
  }
  report.add_note("sample_rate_hz", sc.sample_rate_hz);
  report.add_note("format", std::string(to_string(sc.format)));
  report.add_note("adc_bits", sc.adc.bits);
  report.add_note("hardware_threads", all);
  report.emit(o.json_path);
}

}  // namespace

void add_bench_sim_command(CommandParents& parents) {
  auto o = std::make_shared<BenchSimOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("sim", "IF synthesis speed on one core and all cores, peak memory");
  cmd->add_option("--scenario", o->scenario, "Base scenario (its time, place and clock are used)")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of signal per run")->capture_default_str();
  cmd->add_option("--satellites", o->satellites, "Number of satellites")->capture_default_str();
  cmd->add_option("--format", o->format, "Sample format")->capture_default_str();
  cmd->add_option("--adc-bits", o->adc_bits, "ADC bits")->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF files are written; default: the temp folder");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->callback([o] { run_bench(*o); });
}

}  // namespace deepnav::cli
