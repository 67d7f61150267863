// `deepnav bench align`: the options of the alignment benchmark (tools/bench/align_bench.hpp).
#include "tools/bench/align_bench.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_align_command(CommandParents& parents) {
  auto opt = std::make_shared<AlignBenchSettings>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "align", "Coarse alignment error analysis (paper 000), stationarity check and fine-alignment convergence");
  cmd->add_option("--json", opt->json_path, "Write the tables as JSON to FILE");
  cmd->add_option("--plots", opt->plots_dir, "Write PNG plots (and their data) into DIR");
  cmd->add_option("--runs", opt->runs, "Fine-alignment Monte Carlo runs per grade")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", opt->seed, "Seed of the random generator");
  cmd->callback([opt] { run_align_bench(*opt); });
}

}  // namespace deepnav::cli
