#pragma once
// Where `deepnav run` and `deepnav acquire` get their samples: an IF file path (with its
// metadata file, or flags), tcp://HOST:PORT, udp://HOST:PORT (subscribe to a `deepnav serve`)
// or udp://@HOST:PORT (listen for datagrams sent there), framed (deepnav protocol) or raw
// (bare samples), or rtltcp://HOST:PORT (an rtl_tcp server with an RTL-SDR dongle). The
// addresses' grammar is receiver/sources/source_url.hpp.
#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "receiver/sources/file_sample_source.hpp"
#include "receiver/sources/sample_source.hpp"
#include "receiver/sources/source_settings.hpp"

namespace deepnav {

struct SourceRequest {
  std::string input;  ///< file path or URL
  std::string format = "ibyte";
  double fs_hz = 0.0;  ///< required for files and raw streams; checked against a framed stream's header
  double if_hz = 0.0;
  double skip_s = 0.0;  ///< files only
  bool inverted = false;
  bool raw = false;  ///< streams only: bare samples without the deepnav framing
  double reconnect_timeout_s = 30.0;
  const std::atomic<bool>* stop = nullptr;  ///< once set, the source ends (Ctrl-C)
  /// An ION GNSS SDR metadata file (XML) describing the file: its format, rate, IF,
  /// inversion and, when --input is empty, the file itself. Files only.
  std::string metadata;
  /// Which flags the command line gave: with --metadata they override its values (warned).
  bool format_given = false, fs_given = false, if_given = false, inverted_given = false;
  /// The sample rates the command takes: --fs is checked against them as it is parsed, a
  /// metadata file's rate here.
  double min_fs_hz = 0.0, max_fs_hz = std::numeric_limits<double>::infinity();
  /// rtltcp:// only: tuner gain in dB or "auto" (the tuner's AGC), the RTL2832's digital
  /// AGC, crystal correction (ppm), bias tee (power for an active antenna).
  std::string rtl_gain = "auto";
  bool rtl_agc = false;
  int rtl_ppm = 0;
  bool rtl_bias_tee = false;
};

struct OpenedSource {
  std::unique_ptr<SampleSource> source;
  std::string input;  ///< the file path or URL read (a metadata file's <file> when --input was not given)
  std::optional<double> duration_s;  ///< the signal length, when known in advance (files)
  bool is_stream = false;
  /// For the run summary: transport statistics of a stream (null for files).
  std::function<nlohmann::json()> report;
  /// Why a stream failed (protocol error, connection lost for good), once it has.
  std::function<std::optional<std::string>()> failure;
  /// True once the run was stopped by `stop`.
  std::function<bool()> interrupted;
  /// How the samples are read and where each setting came from (messages name them).
  SourceSettings settings;
};

/// Opens the source; throws InputError naming the input and the problem.
OpenedSource open_sample_source(const SourceRequest& request);

/// A file source's options from --input, --metadata and the flags (what `run` and
/// `acquire` read); throws InputError naming the file, flag or metadata element.
FileSampleSourceOptions file_source_options(const SourceRequest& request);
/// The same, and in `settings` (when not null) where each setting came from.
FileSampleSourceOptions file_source_options(const SourceRequest& request, SourceSettings* settings);

}  // namespace deepnav
