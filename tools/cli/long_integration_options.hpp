#pragma once
// The ultra-tight long-integration options, shared by every command that runs the aided
// receiver on IF (`deepnav run`, `deepnav bench threshold`, `deepnav bench jam`).
#include <CLI/CLI.hpp>

#include "aiding/long_integrator.hpp"

namespace deepnav::cli {

/// Adds --coherent-ms and --noncoherent-ms (multiples of 20 ms, 20 to 2000) to `cmd`; they
/// set `config`, which must outlive the parse.
void add_long_integration_options(CLI::App& cmd, aiding::LongIntegrationConfig& config);

/// "200 ms coherent (data wiped), 200 ms non-coherent": what a report says was used.
std::string describe(const aiding::LongIntegrationConfig& config);

}  // namespace deepnav::cli
