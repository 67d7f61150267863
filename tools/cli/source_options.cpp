#include "tools/cli/source_options.hpp"

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/gnss_receiver.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sample_format.hpp"
#include "tools/cli/cli_checks.hpp"

namespace deepnav::cli {
namespace {

/// The sample rates the consumer of the samples takes: the FFT search needs at least one
/// sample per chip, the tracking channels their own minimum.
struct SampleRateRange {
  double min_hz, max_hz;
};

SampleRateRange sample_rates_for(SourceUse use) {
  if (use == SourceUse::acquisition) return {gps::kCodeRate_cps, kMaxAcquisitionSampleRate_hz};
  return {kMinSampleRate_hz, kMaxSampleRate_hz};
}

/// --input: an existing file for the acquisition; a file or a stream URL for the receiver
/// (the factory checks which, so that a URL is not taken for a missing file).
void add_input_option(CLI::App& cmd, SourceRequest& r, SourceUse use) {
  if (use == SourceUse::acquisition) {
    cmd.add_option("--input", r.input, "IF sample file")->check(CLI::ExistingFile);
    return;
  }
  cmd.add_option("--input", r.input,
                 "IF sample file, tcp://HOST:PORT, udp://HOST:PORT (subscribe), udp://@HOST:PORT (listen) or "
                 "rtltcp://HOST:PORT (an rtl_tcp server: RTL-SDR, cu8 at --fs, default 2048000)");
}

/// The options only a stream reads: its framing and how long a dropped one is retried.
void add_stream_options(CLI::App& cmd, SourceRequest& r) {
  cmd.add_flag("--raw", r.raw, "The stream is bare samples (no deepnav framing): needs --format and --fs");
  cmd.add_option("--reconnect-timeout", r.reconnect_timeout_s, "Seconds a dropped stream is retried (with backoff)")
      ->check(finite_in(0.0, 86400.0, "seconds"))
      ->capture_default_str();
}

/// The rtltcp:// dongle's settings.
void add_rtl_options(CLI::App& cmd, SourceRequest& r) {
  cmd.add_option("--rtl-gain", r.rtl_gain, "rtltcp://: tuner gain in dB (the nearest step), or auto (the tuner's AGC)")
      ->capture_default_str();
  cmd.add_flag("--rtl-agc", r.rtl_agc, "rtltcp://: switch on the RTL2832's digital AGC");
  cmd.add_option("--rtl-ppm", r.rtl_ppm, "rtltcp://: crystal frequency correction (ppm)")->capture_default_str();
  cmd.add_flag("--rtl-bias-tee", r.rtl_bias_tee, "rtltcp://: power an active antenna through the coax (bias tee)");
}

}  // namespace

void add_source_options(CLI::App& cmd, SourceRequest& r, SourceUse use) {
  const bool streams = use == SourceUse::receiver;
  const SampleRateRange rates = sample_rates_for(use);
  r.min_fs_hz = rates.min_hz;
  r.max_fs_hz = rates.max_hz;
  add_input_option(cmd, r, use);
  cmd.add_option("--metadata", r.metadata,
                 "ION GNSS SDR metadata file (XML) describing the IF file: its format, rate, IF and inversion, and "
                 "the file itself unless --input names it; flags given as well override it")
      ->check(CLI::ExistingFile);
  cmd.add_option("--format", r.format, sample_format_choices())->capture_default_str();
  cmd.add_option("--fs", r.fs_hz,
                 streams ? "Sample rate (Hz); a framed stream's header carries it"
                         : "Sample rate (Hz); required without --metadata")
      ->check(finite_in(rates.min_hz, rates.max_hz, "a sample rate in Hz"));
  if (streams) add_stream_options(cmd, r);
  cmd.add_option("--if", r.if_hz,
                 streams ? "Intermediate frequency (Hz); rtltcp://: the dongle is tuned to 1575.42 MHz minus it"
                         : "Intermediate frequency (Hz), 0 for complex baseband")
      ->check(finite_in(-rates.max_hz / 2, rates.max_hz / 2, "a frequency in Hz, below half the sample rate"))
      ->capture_default_str();
  if (streams) add_rtl_options(cmd, r);
  cmd.add_option("--skip", r.skip_s, "Seconds skipped at the start of the file")
      ->check(finite_in(0.0, 1e7, "seconds"))
      ->capture_default_str();
  cmd.add_flag("--inverted-spectrum", r.inverted, "The front end delivers I - jQ");
}

void note_given_source_options(const CLI::App& cmd, SourceRequest& r) {
  r.format_given = cmd.count("--format") > 0;
  r.fs_given = cmd.count("--fs") > 0;
  r.if_given = cmd.count("--if") > 0;
  r.inverted_given = cmd.count("--inverted-spectrum") > 0;
}

}  // namespace deepnav::cli
