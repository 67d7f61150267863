// `deepnav bench stream`: the options of the loopback streaming benchmark
// (tools/bench/stream_bench.hpp).
#include "tools/bench/stream_bench.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives

void add_bench_stream_command(CommandParents& parents) {
  auto o = std::make_shared<StreamBenchSettings>();
  CLI::App* cmd = parents.bench.add_subcommand(
      "stream", "Loopback streaming: throughput server -> receiver (MB/s, x real time) and CPU at real-time pace");
  cmd->add_option("--scenario", o->scenario_path, "Scenario (made to have every satellite above the horizon, up to 12)")
      ->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of signal for the as-fast-as-possible run")
      ->capture_default_str();
  cmd->add_option("--paced", o->paced_s, "Seconds of signal for the real-time run")->capture_default_str();
  cmd->add_option("--json", o->json_path, "Also write the figures as JSON");
  cmd->callback([o] { run_stream_bench(*o); });
}

}  // namespace deepnav::cli
