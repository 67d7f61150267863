#include "tools/cli/summary_file.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

namespace deepnav::cli {

SummaryFile::SummaryFile(const std::string& path) : file_(path) {
  try {
    file_.reserve(kSummaryReserveBytes);
  } catch (const std::runtime_error& e) {
    spdlog::warn("{}: the summary may not fit if the other products fill the disk", e.what());
  }
}

void SummaryFile::write(const nlohmann::json& summary) {
  file_.write(summary.dump(2) + "\n");
  file_.commit();
}

}  // namespace deepnav::cli
