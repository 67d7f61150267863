// The deepnav command line. Each subcommand is added from its own file (commands.hpp) and
// does its work in a CLI11 callback, so errors surface from app.parse().
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <iostream>

#include "tools/cli/commands.hpp"
#include "tools/cli/yaml_config.hpp"

int main(int argc, char** argv) {
  using namespace deepnav::cli;
  // Logs go to stderr so that stdout carries only results (tables, JSON).
  spdlog::set_default_logger(spdlog::stderr_logger_st("deepnav"));
  spdlog::set_pattern("%^%l%$: %v");
  spdlog::set_level(spdlog::level::info);

  CLI::App app{"deepnav: software GPS L1 C/A receiver with ultra-tight INS aiding"};
  app.require_subcommand(1);
  add_yaml_config(app);
  app.add_flag_callback(
      "-v,--verbose", [] { spdlog::set_level(spdlog::level::debug); }, "Log debug messages to stderr");
  app.add_flag_callback(
      "-q,--quiet", [] { spdlog::set_level(spdlog::level::warn); }, "Log only warnings and errors");
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks: each prints a table, and writes JSON with --json FILE");
  bench->require_subcommand(1);
  CommandParents parents{app, *bench};
  add_acquire_command(parents);
  add_bench_align_command(parents);
  add_bench_coupling_command(parents);
  add_bench_jam_command(parents);
  add_bench_leverarm_command(parents);
  add_bench_rx_command(parents);
  add_bench_sim_command(parents);
  add_bench_snapshot_command(parents);
  add_bench_stream_command(parents);
  add_bench_threshold_command(parents);
  add_fuse_command(parents);
  add_nav_command(parents);
  add_run_command(parents);
  add_serve_command(parents);
  add_sim_command(parents);
  add_snap_command(parents);

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
