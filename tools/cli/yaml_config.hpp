#pragma once
// A command's options read from, and written to, a YAML file: `deepnav run --config
// run.yaml` and `deepnav run ... --print-config`. The keys are the command's long option
// names without the dashes (`imu-grade`, or `imu_grade`), so every flag is a key and a
// new flag needs no work here. Values given on the command line win over the file's.
// `--config` is the root app's option (CLI11 reads configuration files only there); the
// subcommands pass it up (fallthrough), and the file sets the options of whichever
// command the line names.
//
// The file is checked before any option sees it: a key that is not an option, a map
// where a value belongs, or a number that does not parse is an error naming the file,
// the line and the key (with the nearest option name for a misspelt one).
#include <CLI/CLI.hpp>
#include <string>

namespace deepnav::cli {

class YamlConfig : public CLI::Config {
 public:
  /// `root`: the app holding --config (outlives this formatter).
  explicit YamlConfig(CLI::App& root) : root_(root) {}

  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override;
  /// The effective configuration: every option's value (given, or its default), one key a
  /// line, each after a comment with the option's help when `write_description`.
  std::string to_config(const CLI::App* app, bool default_also, bool write_description,
                        std::string prefix) const override;

 private:
  std::string file_name() const;
  CLI::App& root_;  // not const: CLI11 hands out an option's validators only from a mutable one
};

/// Adds `--config FILE` (YAML, see above) to the root app; call before adding subcommands.
void add_yaml_config(CLI::App& root);

/// Adds `--print-config` to `command`: after the parse, `print_requested` says whether to
/// print `effective_config(command)` and stop.
void add_print_config(CLI::App& command, bool& print_requested);

/// What --print-config prints: a YAML file that reproduces this run with --config.
std::string effective_config(CLI::App& command);

}  // namespace deepnav::cli
