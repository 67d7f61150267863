// `deepnav bench jam` and `deepnav bench jam-point`: the jamming sweep's options; the sweep
// and its points are tools/bench/jam_sweep.hpp and tools/bench/jam_point.hpp.
#include <fmt/format.h>

#include <filesystem>

#include "receiver/mitigation/mitigation_config.hpp"
#include "tools/bench/jam_point.hpp"
#include "tools/bench/jam_sweep.hpp"
#include "tools/bench/receiver_modes.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/long_integration_options.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_jam_command(CommandParents& parents) {
  auto o = std::make_shared<JamSweepSettings>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "jam", "Jamming sweep: J/S thresholds per jammer, receiver mode and mitigation (CSV, table, plots)");
  cmd->add_option("--scenario", o->scenario, "Base scenario (the jammer is added from --onset)")->capture_default_str();
  cmd->add_option("--jammer", o->jammers, "cw, chirp, wideband, pulsed (comma-separated list)")->capture_default_str();
  cmd->add_option("--js", o->js, "J/S sweep FROM:TO:STEP (dB)")->capture_default_str();
  std::string mode_names;
  for (const auto& m : receiver_modes()) mode_names += (mode_names.empty() ? "" : ", ") + m.name;
  cmd->add_option("--modes", o->modes, "Receiver modes (available: " + mode_names + ")")->capture_default_str();
  cmd->add_option("--mitigation", o->mitigations, "Mitigations: none, notch, excision, blanking, auto (list)")
      ->capture_default_str();
  cmd->add_option("--runs", o->runs, "Seeds per point (scenario seed, +1, ...)")->capture_default_str();
  cmd->add_option("--onset", o->onset_s, "Jammer onset (s); the figures cover onset to end")->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Sweep folder (points/, runs.csv, thresholds.md, PNGs)")->required();
  cmd->add_option("--jobs", o->jobs, "Points run at the same time")->capture_default_str();
  add_long_integration_options(*cmd, o->long_integration);
  cmd->add_flag("--list-commands", o->list_commands, "Print the unfinished points' commands, one a line, and stop");
  cmd->add_flag("--no-plots", o->no_plots, "Skip the PNG plots");
  cmd->add_option("--json", o->json_path, "Write the threshold table as JSON to this file");
  add_systems_option(*cmd, o->systems);
  cmd->callback([o] { run_jam_sweep(*o); });

  // The options jam_point_command writes for each point of the sweep.
  auto p = std::make_shared<JamPoint>();
  auto out = std::make_shared<std::string>();
  CLI::App* point =
      parents.bench.add_subcommand("jam-point", "One point of `deepnav bench jam` (writes OUT/points/ID/point.json)");
  point->add_option("--scenario", p->scenario, "Base scenario")->required();
  point->add_option("--jammer", p->jammer, "cw, chirp, wideband, pulsed")->required();
  point->add_option("--js", p->js_db, "J/S (dB)")->required();
  point->add_option("--mode", p->mode, "Receiver mode")->capture_default_str();
  point->add_option("--mitigation", p->mitigation, "none, notch, excision, blanking, auto")
      ->check(CLI::IsMember(mitigation_mode_names()))
      ->capture_default_str();
  point->add_option("--seed", p->seed, "Seed of noise and jammer")->capture_default_str();
  point->add_option("--onset", p->onset_s, "Jammer onset (s)")->capture_default_str();
  add_long_integration_options(*point, p->long_integration);
  add_systems_option(*point, p->systems);
  point->add_option("--out", *out, "Sweep folder")->required();
  point->callback(
      [p, out] { fmt::print("{}\n", jam_point_summary(run_jam_point(*p, std::filesystem::absolute(*out).string()))); });
}

}  // namespace deepnav::cli
