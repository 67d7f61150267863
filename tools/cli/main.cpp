// The deepnav command line. Subcommands register themselves (command_registry.hpp)
// and do their work in CLI11 callbacks, so errors surface from app.parse().
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <iostream>

#include "tools/cli/command_registry.hpp"
#include "tools/cli/yaml_config.hpp"

namespace deepnav::cli {
std::vector<CommandRegistrar>& command_registry() {
  static std::vector<CommandRegistrar> registry;
  return registry;
}
}  // namespace deepnav::cli

int main(int argc, char** argv) {
  using namespace deepnav::cli;
  // Logs go to stderr so that stdout carries only results (tables, JSON).
  spdlog::set_default_logger(spdlog::stderr_logger_st("deepnav"));
  spdlog::set_pattern("%^%l%$: %v");
  spdlog::set_level(spdlog::level::info);

  CLI::App app{"deepnav: software GPS L1 C/A receiver with ultra-tight INS aiding"};
  app.require_subcommand(1);
  add_yaml_config(app);
  app.add_flag_callback("-v,--verbose", [] { spdlog::set_level(spdlog::level::debug); }, "Log debug messages to stderr");
  app.add_flag_callback("-q,--quiet", [] { spdlog::set_level(spdlog::level::warn); }, "Log only warnings and errors");
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks: each prints a table, and writes JSON with --json FILE");
  bench->require_subcommand(1);
  CommandParents parents{app, *bench};
  for (auto& registrar : command_registry()) registrar(parents);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const UserError& e) {
    std::cerr << "deepnav: " << e.what() << '\n';
    return e.exit_code;
  } catch (const deepnav::InputError& e) {
    std::cerr << "deepnav: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "deepnav: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
