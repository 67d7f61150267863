// `deepnav bench leverarm`: the options of the lever-arm benchmark
// (tools/bench/leverarm_bench.hpp).
#include "tools/bench/leverarm_bench.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_leverarm_command(CommandParents& parents) {
  auto opt = std::make_shared<LeverArmBenchSettings>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "leverarm", "Attitude EKF with lever-arm state (paper 004): Table 1, rate table, 3-D lever arm");
  cmd->add_option("--json", opt->json_path, "Write the tables as JSON to FILE");
  cmd->add_option("--plots", opt->plots_dir, "Write PNG plots (and their data) into DIR");
  cmd->add_option("--runs", opt->runs, "Monte Carlo runs per lever arm")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", opt->seed, "Base seed of the random generators");
  cmd->callback([opt] { run_leverarm_bench(*opt); });
}

}  // namespace deepnav::cli
