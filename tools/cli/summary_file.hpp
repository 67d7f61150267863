#pragma once
// summary.json of `run` and `fuse`: what the run did and what went wrong. It is written
// last, so its disk space is set aside when the run starts: products that fill the disk
// (tracking.csv) fail on their own, and the summary that says so is still written.
#include <nlohmann/json.hpp>
#include <string>

#include "signals/text_output_file.hpp"

namespace deepnav::cli {

/// Space set aside for the summary (a long aided run's summary is a few tens of kB).
inline constexpr std::uint64_t kSummaryReserveBytes = 256 * 1024;

class SummaryFile {
 public:
  /// Creates the partial file and reserves kSummaryReserveBytes (a warning when the space
  /// is not there: the summary is then written if the disk has room at the end).
  explicit SummaryFile(const std::string& path);
  /// Writes `summary` and gives the file its final name; throws naming the file.
  void write(const nlohmann::json& summary);
  void fail() noexcept { file_.fail(); }

 private:
  TextOutputFile file_;
};

}  // namespace deepnav::cli
