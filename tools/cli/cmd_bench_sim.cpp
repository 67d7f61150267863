// `deepnav bench sim`: the options of the synthesis speed benchmark
// (tools/bench/sim_speed_bench.hpp).
#include "tools/bench/sim_speed_bench.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_sim_command(CommandParents& parents) {
  auto o = std::make_shared<SimSpeedSettings>();
  CLI::App* cmd = parents.bench.add_subcommand("sim", "IF synthesis speed on one core and all cores, peak memory");
  cmd->add_option("--scenario", o->scenario, "Base scenario (its time, place and clock are used)")
      ->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of signal per run")->capture_default_str();
  cmd->add_option("--satellites", o->satellites, "Number of satellites (of each system)")->capture_default_str();
  cmd->add_option_function<std::string>(
      "--systems", [o](const std::string& text) { o->systems = cli::parse_systems_option(text); },
      "Override the scenario's systems: gps, galileo or gps,galileo (Galileo needs a scenario whose navigation "
      "file has Galileo records, e.g. data/scenarios/static_gps_galileo_60s.yaml)");
  cmd->add_option("--format", o->format, "Sample format")->capture_default_str();
  cmd->add_option("--adc-bits", o->adc_bits, "ADC bits")->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF files are written; default: the temp folder");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->callback([o] { run_sim_speed_bench(*o); });
}

}  // namespace deepnav::cli
