#include "tools/bench/sim_speed_bench.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <thread>

#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/process_usage.hpp"

namespace deepnav::bench {

std::string default_sim_speed_scenario() { return source_tree_path("data/scenarios/default.yaml"); }

void run_sim_speed_bench(const SimSpeedSettings& o) {
  Scenario sc = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  sc.duration_s = o.duration_s;
  sc.max_satellites = o.satellites;
  if (!o.systems.empty()) sc.systems = o.systems;
  sc.elevation_mask_rad = 0.0;
  sc.format = parse_sample_format(o.format);
  sc.adc.bits = o.adc_bits;
  validate_scenario(sc);
  const NavData nav = read_rinex_nav(sc.nav_file);
  const std::string work = bench_scratch_dir(o.work_dir, "bench_sim");

  BenchReport report("IF synthesis speed",
                     {"threads", "satellites", "signal_s", "wall_s", "x_real_time", "ns_per_sample", "peak_rss_mib"});
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
  // Which systems only where Galileo is in, which keeps a GPS run's report as it was.
  if (!is_gps_only(sc.systems)) report.add_note("systems", systems_list(sc.systems));
  report.emit(o.json_path);
}

}  // namespace deepnav::bench
