// `deepnav bench coupling`: paper 003's loose/tight/ultra-tight comparison; the options of
// the sweep in tools/bench/coupling_sweep.hpp (which coupling_point_command writes back for
// each point).
#include "tools/bench/coupling_sweep.hpp"
#include "tools/cli/atmosphere_options.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/progress.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_coupling_command(CommandParents& parents) {
  auto o = std::make_shared<CouplingSweepSettings>();
  CouplingPointSettings& pt = o->point;
  CLI::App* cmd =
      parents.bench.add_subcommand("coupling", "Paper 003: loose/tight/ultra-tight position errors per trajectory");
  cmd->add_option("--trajectories", o->trajectories, "Trajectory presets")->delimiter(',')->capture_default_str();
  cmd->add_option("--modes", pt.modes, "Modes")->delimiter(',')->capture_default_str();
  cmd->add_option("--runs", o->runs, "Monte Carlo runs per trajectory (seeds fixed)")->capture_default_str();
  cmd->add_option("--first-run", o->first_run, "Index of the first run (a slice of a larger sweep)")
      ->capture_default_str();
  cmd->add_option("--errors", pt.errors, "Error world preset: none, open-sky, suburban, urban")->capture_default_str();
  cmd->add_option("--duration", pt.duration_s, "Scenario length (s)")->capture_default_str();
  cmd->add_option("--score-at", o->score_at_s, "Time of the 1-sigma figures (s)")->capture_default_str();
  cmd->add_option("--imu-grade", pt.imu_grade, "IMU grade (data/imu_grades.yaml)")->capture_default_str();
  cmd->add_option("--scenario", pt.base_scenario, "Base scenario (signal, clock, IMU lever arm)")
      ->capture_default_str();
  cmd->add_option("--seed", pt.seed, "Base seed")->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "Scenarios run at once")->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Folder of finished points (points/*.json): a rerun resumes from it");
  cmd->add_flag("--filter-troposphere", pt.filter_troposphere,
                "Tight and ultra-tight: estimate a zenith troposphere residual (an 18th state)");
  cmd->add_flag("--filter-ionosphere", pt.filter_ionosphere,
                "Tight and ultra-tight: estimate the ionosphere model's scale error (a 19th state)");
  add_systems_option(*cmd, pt.systems);
  cmd->add_flag("--list-commands", o->list_commands, "Print one command per unfinished point and stop");
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF files are written");
  cmd->add_option("--csv", o->csv_path, "Per-epoch errors of every run");
  cmd->add_option("--plot", o->plot_path, "PNG of error over time for the circle cases (needs --csv)");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  add_atmosphere_options(*cmd, pt.atmosphere);
  cmd->callback([o] {
    ProgressLine progress("coupling", 0.0);
    run_coupling_sweep(*o, [&progress](double done) {
      progress.update(done);
      if (done >= 1.0) progress.finish();  // before the report is printed
    });
  });
}

}  // namespace deepnav::cli
