// `deepnav bench threshold`: the options of the weak-signal threshold benchmark
// (tools/bench/threshold_bench.hpp).
#include "tools/bench/threshold_bench.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/long_integration_options.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_threshold_command(CommandParents& parents) {
  auto o = std::make_shared<ThresholdBenchSettings>();
  CLI::App* cmd =
      parents.bench.add_subcommand("threshold", "Lowest C/N0 at which the scalar loops keep lock (C/N0 ramp)");
  cmd->add_option("--scenario", o->scenario, "Base scenario (static)")->capture_default_str();
  cmd->add_option("--start", o->start_dbhz, "C/N0 before the ramp (dB-Hz)")->capture_default_str();
  cmd->add_option("--ramp-start", o->ramp_start_s, "Ramp start (s)")->capture_default_str();
  cmd->add_option("--rate", o->rate_dbps, "C/N0 fall rate (dB/s)")->capture_default_str();
  cmd->add_option("--end", o->end_dbhz, "Lowest C/N0 (dB-Hz)")->capture_default_str();
  cmd->add_option("--modes", o->modes,
                  "Instead: each of these modes (scalar,loose,tight,ultra) on the land circle with an IMU; the C/N0 at "
                  "which it stops holding a 10 m solution from satellite measurements")
      ->delimiter(',');
  cmd->add_option("--aided-scenario", o->aided_scenario, "Scenario for --modes (needs an imu section)")
      ->capture_default_str();
  cmd->add_option("--imu-grade", o->imu_grade,
                  "With --modes: this IMU grade instead of the scenario's (e.g. consumer)");
  cmd->add_option("--oscillator", o->oscillator,
                  "With --modes: this receiver oscillator instead of the scenario's (ideal, tcxo, ocxo)")
      ->check(CLI::IsMember({"ideal", "tcxo", "ocxo"}));
  add_long_integration_options(*cmd, o->long_integration);
  add_systems_option(*cmd, o->systems);
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF file is written");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->callback([o] {
    o->long_integration_text = describe(o->long_integration);  // the report says it as the options do
    run_threshold_bench(*o);
  });
}

}  // namespace deepnav::cli
