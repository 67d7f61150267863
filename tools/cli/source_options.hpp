#pragma once
// The sample-source options (--input, --metadata, --format, --fs, --if, --skip,
// --inverted-spectrum, and for the receiver the stream ones: --raw, --reconnect-timeout,
// --rtl-*), declared once for every command that reads IF samples, so that their names,
// help, checks and the record of which were given read alike everywhere.
#include <CLI/CLI.hpp>

#include "receiver/sources/sample_source_factory.hpp"

namespace deepnav::cli {

/// What reads the samples: it sets what --input may name and the sample rates accepted.
enum class SourceUse {
  acquisition,  ///< `deepnav acquire`: an existing file (or --metadata), rates the FFT search takes
  receiver,     ///< `deepnav run`: a file or a stream URL, rates the receiver takes
};

/// Adds the source options to `cmd`, in the order its --help and --print-config list them;
/// they set `request`, which must outlive the parse.
void add_source_options(CLI::App& cmd, SourceRequest& request, SourceUse use);

/// After the parse (in the command's callback): records in `request` which of --format,
/// --fs, --if and --inverted-spectrum were given (on the line or in a --config file), the
/// ones that override a --metadata file's values.
void note_given_source_options(const CLI::App& cmd, SourceRequest& request);

}  // namespace deepnav::cli
