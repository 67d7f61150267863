#pragma once
// The deepnav subcommands, one file each (tools/cli/cmd_NAME.cpp), each adding itself to the
// root app (`deepnav NAME`) or to `deepnav bench NAME`. main.cpp lists them, in this order,
// which is also the order of `deepnav --help`.
#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "ins/input_error.hpp"

namespace deepnav::cli {

/// Parent apps a command can attach to: the root (`deepnav X`) or `deepnav bench X`.
struct CommandParents {
  CLI::App& root;
  CLI::App& bench;
};

void add_acquire_command(CommandParents& parents);
void add_bench_align_command(CommandParents& parents);
void add_bench_coupling_command(CommandParents& parents);
void add_bench_jam_command(CommandParents& parents);
void add_bench_leverarm_command(CommandParents& parents);
void add_bench_rx_command(CommandParents& parents);
void add_bench_sim_command(CommandParents& parents);
void add_bench_snapshot_command(CommandParents& parents);
void add_bench_stream_command(CommandParents& parents);
void add_bench_threshold_command(CommandParents& parents);
void add_fuse_command(CommandParents& parents);
void add_nav_command(CommandParents& parents);
void add_run_command(CommandParents& parents);
void add_serve_command(CommandParents& parents);
void add_sim_command(CommandParents& parents);
void add_snap_command(CommandParents& parents);

/// Exit status of `run` and `acquire` when the signal held nothing to find: no satellite
/// acquired, or too little signal for one observation epoch (or one coherent block). The
/// others: 0 success, 1 an error (bad input, a failed product), CLI11's 100-127 for a
/// command line it cannot parse.
inline constexpr int kExitNothingFound = 3;

/// Thrown by a command for a user error: main prints "deepnav: <message>" and exits with `exit_code`
/// (an InputError from a library exits with 1).
struct UserError : InputError {
  explicit UserError(const std::string& message, int code = 1) : InputError(message), exit_code(code) {}
  int exit_code;
};

}  // namespace deepnav::cli
