// `deepnav bench snapshot`: the options of the snapshot accuracy benchmark
// (tools/bench/snapshot_bench.hpp).
#include "tools/bench/snapshot_bench.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engine this command drives

void add_bench_snapshot_command(CommandParents& parents) {
  auto o = std::make_shared<SnapshotBenchSettings>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "snapshot", "Horizontal error of deepnav snap against snapshot length (synthesized scenarios, seeded hints)");
  cmd->add_option("--scenario", o->scenarios, "Scenarios (default: static_120s and land_circle_60s)");
  cmd->add_option("--points", o->points, "Snapshot points per scenario")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--lengths", o->lengths_ms, "Snapshot lengths (ms, 2-100)")->delimiter(',')->capture_default_str();
  cmd->add_option("--max-time-error", o->max_time_error_s, "Time hints off by up to this (s, either sign)")
      ->check(finite_in(0.0, 3600.0, "a time in s"))
      ->capture_default_str();
  cmd->add_flag("!--no-position-hint", o->position_hint, "Solve without a position hint");
  cmd->add_option("--max-hint-offset", o->max_hint_offset_m, "Position hints off by up to this (m)")
      ->check(finite_in(0.0, 149e3, "a distance in m"))
      ->capture_default_str();
  cmd->add_option("--cn0", o->cn0_dbhz, "C/N0 of every satellite (dB-Hz)")
      ->check(finite_in(20.0, 60.0, "a C/N0 in dB-Hz"))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the hints' errors")->capture_default_str();
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->add_option("--plots-dir", o->plots_dir, "Write each snapshot's error and the PNG plot here");
  cmd->callback([o] { run_snapshot_bench(*o); });
}

}  // namespace deepnav::cli
