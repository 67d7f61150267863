#include "tools/long_integration_options.hpp"

#include <fmt/format.h>

namespace deepnav::cli {
namespace {

CLI::Validator multiple_of_bits() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        int ms = 0;
        try {
          std::size_t used = 0;
          ms = std::stoi(text, &used);
          if (used != text.size()) return "expected a whole number of milliseconds, got '" + text + "'";
        } catch (const std::exception&) {
          return "expected a whole number of milliseconds, got '" + text + "'";
        }
        if (ms < 20 || ms > 2000 || ms % 20 != 0)
          return "expected a multiple of 20 ms (one data bit) from 20 to 2000, got " + text;
        return {};
      },
      "MS (multiple of 20)");
}

}  // namespace

void add_long_integration_options(CLI::App& cmd, aiding::LongIntegrationConfig& config) {
  cmd.add_option("--coherent-ms", config.coherent_ms,
                 "Ultra-tight, weak signals: coherent integration with the data bits wiped off (ms; 20: no wipe-off)")
      ->check(multiple_of_bits())
      ->capture_default_str();
  cmd.add_option("--noncoherent-ms", config.noncoherent_ms,
                 "Ultra-tight, weak signals: 20 ms bits whose data are not predicted are summed in power over this (ms)")
      ->check(multiple_of_bits())
      ->capture_default_str();
  cmd.add_flag("--assist-data-bits", config.assist_data_bits,
               "Ultra-tight: predict subframes 1-3 from the assisted ephemeris (--ephemeris-from) before they are "
               "decoded (checked against the signal bit by bit)");
}

std::string describe(const aiding::LongIntegrationConfig& c) {
  if (c.coherent_ms <= 20) return fmt::format("no data wipe-off: 20 ms bits, {} ms non-coherent", c.noncoherent_ms);
  return fmt::format("{} ms coherent with data wipe-off{}, {} ms non-coherent where the bits are not predicted "
                     "(below {} dB-Hz)",
                     c.coherent_ms, c.assist_data_bits ? " (subframes 1-3 assisted from the navigation file)" : "",
                     c.noncoherent_ms, c.enter_below_dbhz);
}

}  // namespace deepnav::cli
