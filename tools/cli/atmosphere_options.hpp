#pragma once
// The receiver's atmosphere model options, shared by every command that runs the receiver
// (`deepnav run`, `deepnav bench coupling`), so that they read and check the names alike.
#include <CLI/CLI.hpp>

#include "receiver/pvt/atmosphere_models.hpp"

namespace deepnav::cli {

/// Adds --ionosphere klobuchar|none and --troposphere saastamoinen|none to `cmd`; they set
/// `models` (which must outlive the parse) and leave it as it is when not given. An
/// unknown name fails the parse with the list of accepted ones.
void add_atmosphere_options(CLI::App& cmd, AtmosphereModels& models);

}  // namespace deepnav::cli
