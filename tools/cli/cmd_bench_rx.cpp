// `deepnav bench rx`: the options of the receiver speed benchmark
// (tools/bench/rx_speed_bench.hpp).
#include "tools/bench/rx_speed_bench.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_rx_command(CommandParents& parents) {
  auto o = std::make_shared<RxSpeedSettings>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "rx", "Receiver real-time factor (8/12 channels, 1 thread/all cores, ultra) and correlator throughput");
  cmd->add_option("--scenario", o->scenario, "Scenario with 12 satellites and an imu section")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Signal length (s)")->capture_default_str();
  cmd->add_option("--repeats", o->repeats, "Runs per receiver case; the median is reported")
      ->check(CLI::Range(1, 99))
      ->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Where the (deleted) IF file is written");
  cmd->add_option("--json", o->json_path, "Write the figures as JSON to this file");
  cmd->add_option(
      "--kernel", o->kernel,
      "Correlator kernel for the receiver runs (portable, avx2, avx512, neon; default: the CPU's fastest, or "
      "DEEPNAV_CORRELATOR_KERNEL)");
  cmd->add_option_function<std::string>(
         "--systems", [o](const std::string& text) { o->systems = parse_systems_option(text); },
         "gps (default), or gps,galileo to add GPS-alone and GPS+Galileo rows on a mixed scenario")
      ->default_str("gps");
  cmd->add_option("--galileo-scenario", o->galileo_scenario, "Scenario with GPS and Galileo satellites (--systems)")
      ->capture_default_str();
  cmd->callback([o] { run_rx_speed_bench(*o); });
}

}  // namespace deepnav::cli
