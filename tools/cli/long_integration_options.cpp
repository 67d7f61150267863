#include "tools/cli/long_integration_options.hpp"

#include <fmt/format.h>

namespace deepnav::cli {
namespace {

/// A whole number of data bits (CLI::Range checks the number and its bounds).
CLI::Validator multiple_of_bits() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        int ms = 0;
        if (!CLI::detail::lexical_cast(text, ms)) return {};  // not a number: Range says so
        return ms % 20 == 0 ? std::string() : fmt::format("expected a multiple of 20 ms (one data bit), got {}", text);
      },
      "multiple of 20");
}

}  // namespace

void add_long_integration_options(CLI::App& cmd, aiding::LongIntegrationConfig& config) {
  cmd.add_option("--coherent-ms", config.coherent_ms,
                 "Ultra-tight, weak signals: coherent integration with the data bits wiped off (ms; 20: no wipe-off)")
      ->check(CLI::Range(20, 2000) & multiple_of_bits())
      ->capture_default_str();
  cmd.add_option(
         "--noncoherent-ms", config.noncoherent_ms,
         "Ultra-tight, weak signals: 20 ms bits whose data are not predicted are summed in power over this (ms)")
      ->check(CLI::Range(20, 2000) & multiple_of_bits())
      ->capture_default_str();
  cmd.add_flag("--assist-data-bits", config.assist_data_bits,
               "Ultra-tight: predict subframes 1-3 from the assisted ephemeris (--ephemeris-from) before they are "
               "decoded (checked against the signal bit by bit)");
}

std::string describe(const aiding::LongIntegrationConfig& c) {
  if (c.coherent_ms <= 20) return fmt::format("no data wipe-off: 20 ms bits, {} ms non-coherent", c.noncoherent_ms);
  return fmt::format(
      "{} ms coherent with data wipe-off{}, {} ms non-coherent where the bits are not predicted "
      "(below {} dB-Hz)",
      c.coherent_ms, c.assist_data_bits ? " (subframes 1-3 assisted from the navigation file)" : "", c.noncoherent_ms,
      c.enter_below_dbhz);
}

}  // namespace deepnav::cli
