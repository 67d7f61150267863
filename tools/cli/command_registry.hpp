#pragma once
// Each subcommand lives in its own tools/cli/cmd_*.cpp and registers itself here at
// static-initialisation time, so adding a command never touches main.cpp.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "ins/input_error.hpp"

namespace deepnav::cli {

/// Parent apps a command can attach to: the root (`deepnav X`) or `deepnav bench X`.
struct CommandParents {
  CLI::App& root;
  CLI::App& bench;
};

using CommandRegistrar = std::function<void(CommandParents&)>;

std::vector<CommandRegistrar>& command_registry();

/// Usage, at namespace scope in a cmd_*.cpp:
///   const bool registered = deepnav::cli::register_command([](CommandParents& p) { ... });
inline bool register_command(CommandRegistrar registrar) {
  command_registry().push_back(std::move(registrar));
  return true;
}

/// Thrown by a command for a user error: main prints "deepnav: <message>" and exits with `exit_code`
/// (an InputError from a library exits with 1).
struct UserError : InputError {
  explicit UserError(const std::string& message, int code = 1) : InputError(message), exit_code(code) {}
  int exit_code;
};

}  // namespace deepnav::cli
