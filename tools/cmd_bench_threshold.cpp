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

#include "receiver/file_sample_source.hpp"
#include "receiver/scalar_receiver.hpp"
#include "signals/if_synthesizer.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/scenario.hpp"
#include "tools/bench_report.hpp"
#include "tools/command_registry.hpp"

namespace deepnav::cli {
namespace {

struct ThresholdOptions {
  std::string scenario = std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/static_120s.yaml";
  double start_dbhz = 40.0;
  double ramp_start_s = 15.0;
  double rate_dbps = 0.25;  ///< C/N0 fall rate
  double end_dbhz = 15.0;
  std::string json_path;
  std::string work_dir;
};

void run_threshold(const ThresholdOptions& o) {
  Scenario sc = load_scenario(o.scenario, DEEPNAV_SOURCE_DIR);
  const double ramp_s = (o.start_dbhz - o.end_dbhz) / o.rate_dbps;
  sc.duration_s = o.ramp_start_s + ramp_s;
  sc.cn0 = Cn0Spec{};
  sc.cn0.fixed_dbhz = o.start_dbhz;
  sc.cn0.ramp_start_s = o.ramp_start_s;
  sc.cn0.ramp_end_s = o.ramp_start_s + ramp_s;
  sc.cn0.ramp_delta_db = o.end_dbhz - o.start_dbhz;
  validate_scenario(sc);
  const std::string work =
      o.work_dir.empty() ? (std::filesystem::temp_directory_path() / "deepnav_bench_threshold").string() : o.work_dir;
  SynthesisOptions so;
  so.threads = 0;
  so.if_only = false;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(work, so);

  FileSampleSourceOptions src;
  src.path = s.if_path;
  src.format = sc.format;
  src.sample_rate_hz = sc.sample_rate_hz;
  src.intermediate_frequency_hz = sc.if_hz;
  FileSampleSource source(src);
  ReceiverConfig rc;
  rc.reacquire_interval_s = 1e9;  // a channel lost stays lost: the threshold is the loss point
  rc.reference_week = sc.start_time.week;
  ScalarReceiver receiver(rc, source);
  // True Doppler per PRN at the truth rate (sat_truth.csv: t_s, prn, code, doppler_hz, ...).
  std::map<int, std::vector<std::pair<double, double>>> truth_doppler;
  {
    std::ifstream in(s.sat_truth_path);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::stringstream f(line);
      std::string t, prn, code, dop;
      std::getline(f, t, ',');
      std::getline(f, prn, ',');
      std::getline(f, code, ',');
      std::getline(f, dop, ',');
      truth_doppler[std::stoi(prn)].emplace_back(std::stod(t), std::stod(dop));
    }
  }
  const auto doppler_truth = [&](int prn, double t) {
    const auto& v = truth_doppler[prn];
    const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
    return it == v.end() ? v.back().second : it->second;
  };
  std::map<int, double> last_following_s, declared_lost_s;
  receiver.run([](const ReceiverEpoch&) {},
               [&](const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
                 const double t = static_cast<double>(e.first_sample + e.samples) / sc.sample_rate_hz;
                 if (ch.state == ChannelState::tracking &&
                     std::abs(e.carrier_doppler_hz - doppler_truth(e.prn, t)) < 5.0)
                   last_following_s[e.prn] = t;
                 declared_lost_s[e.prn] = t;  // the last epoch the channel produced
               });
  std::filesystem::remove_all(work);

  const auto cn0_at = [&](double t) {
    if (t <= o.ramp_start_s) return o.start_dbhz;
    return std::max(o.end_dbhz, o.start_dbhz - o.rate_dbps * (t - o.ramp_start_s));
  };
  BenchReport report("Scalar tracking threshold (static, C/N0 ramp)",
                     {"prn", "follows_until_s", "threshold_dbhz", "channel_ended_s", "cn0_at_end_dbhz"});
  for (const char* col : {"follows_until_s", "threshold_dbhz", "channel_ended_s", "cn0_at_end_dbhz"})
    report.set_precision(col, 1);
  std::vector<double> thresholds;
  for (const auto& [prn, t] : last_following_s) {
    const double cn0 = cn0_at(t);
    thresholds.push_back(cn0);
    report.add_row({static_cast<long long>(prn), t, cn0, declared_lost_s[prn], cn0_at(declared_lost_s[prn])});
  }
  std::sort(thresholds.begin(), thresholds.end());
  if (!thresholds.empty()) report.add_note("median_threshold_dbhz", thresholds[thresholds.size() / 2]);
  report.add_note("ramp", fmt::format("{} dB-Hz until {} s, then -{} dB/s to {} dB-Hz", o.start_dbhz, o.ramp_start_s,
                                      o.rate_dbps, o.end_dbhz));
  report.add_note("loops", "FLL-assisted PLL 10 Hz (tracking), DLL 0.5 Hz, 10 ms coherent after bit sync");
  report.emit(o.json_path);
}

const bool registered = register_command([](CommandParents& parents) {
  auto o = std::make_shared<ThresholdOptions>();
  CLI::App* cmd = parents.bench.add_subcommand("threshold", "Lowest C/N0 at which the scalar loops keep lock (C/N0 ramp)");
  cmd->add_option("--scenario", o->scenario, "Base scenario (static)")->capture_default_str();
  cmd->add_option("--start", o->start_dbhz, "C/N0 before the ramp (dB-Hz)")->capture_default_str();
  cmd->add_option("--ramp-start", o->ramp_start_s, "Ramp start (s)")->capture_default_str();
  cmd->add_option("--rate", o->rate_dbps, "C/N0 fall rate (dB/s)")->capture_default_str();
  cmd->add_option("--end", o->end_dbhz, "Lowest C/N0 (dB-Hz)")->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF file is written");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->callback([o] { run_threshold(*o); });
});

}  // namespace
}  // namespace deepnav::cli
