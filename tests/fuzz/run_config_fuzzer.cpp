// Command configuration files (tools/cli/yaml_config.hpp, `deepnav run --config FILE`): the
// input is read by the YAML reader for a `run` command holding one option of each kind
// the real commands use (text, number, bounded number, integer range, choice, flag,
// negatable flag, fixed-length list). Errors must be UserError naming the file.
#include <CLI/CLI.hpp>
#include <sstream>

#include "tests/fuzz/fuzz_support.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/yaml_config.hpp"

namespace {

struct Options {
  std::string input, mode = "scalar";
  double fs = 0.0, skip = 0.0;
  int channels = 12;
  unsigned threads = 0;
  bool raw = false, fault_exclusion = true;
  std::vector<double> lever_arm;
};

/// The app, parsed as `deepnav run` so the reader fills that command (built once: CLI11
/// apps are costly to make, and reading a configuration leaves them unchanged).
CLI::App& run_app() {
  static Options o;
  static CLI::App* app = [] {
    auto* root = new CLI::App("deepnav");
    deepnav::cli::add_yaml_config(*root);
    CLI::App* run = root->add_subcommand("run");
    run->add_option("--input", o.input);
    run->add_option("--fs", o.fs);
    run->add_option("--skip", o.skip)->check(CLI::Range(0.0, 1e7));
    run->add_option("--channels", o.channels)->check(CLI::Range(1, 32));
    run->add_option("--threads", o.threads);
    run->add_option("--mode", o.mode)->check(CLI::IsMember({"scalar", "loose", "tight", "ultra"}));
    run->add_flag("--raw", o.raw);
    run->add_flag("--fault-exclusion,!--no-fault-exclusion", o.fault_exclusion);
    run->add_option("--imu-lever-arm", o.lever_arm)->expected(3);
    root->parse("run", false);
    return root;
  }();
  return *app;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  CLI::App& app = run_app();
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  const auto expected = [](const std::exception& e) {
    return deepnav::fuzz::is_a<deepnav::cli::UserError>(e) && deepnav::fuzz::names_input("configuration")(e);
  };
  deepnav::fuzz::guarded([&] { (void)app.get_config_formatter()->from_config(in); }, expected);
  return 0;
}
