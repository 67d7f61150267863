#pragma once
// CLI11 checks for numeric options. CLI::Range lets NaN through (every comparison with it is
// false) and says nothing of infinities; these name the range and reject both.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "signals/satellite_id.hpp"

namespace deepnav::cli {

/// A finite number in [lo, hi] (in words: `what`, e.g. "a sample rate in Hz").
CLI::Validator finite_in(double lo, double hi, const std::string& what = "a number");
/// A finite number greater than lo and at most hi.
CLI::Validator finite_above(double lo, double hi, const std::string& what = "a number");

/// --systems: comma-separated system names ("gps,galileo"), each once; a UserError naming
/// the option otherwise.
std::vector<GnssSystem> parse_systems_option(const std::string& text);
/// A benchmark's --systems option: what the receiver tracks ("gps" by default; the
/// scenario must carry the systems named).
void add_systems_option(CLI::App& cmd, std::vector<GnssSystem>& systems);

}  // namespace deepnav::cli
