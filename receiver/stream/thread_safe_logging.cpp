#include "receiver/stream/thread_safe_logging.hpp"

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace deepnav {

void use_thread_safe_logger() {
  static bool done = false;
  if (done) return;
  done = true;
  const auto level = spdlog::get_level();
  auto logger = spdlog::stderr_logger_mt("deepnav-mt");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%^%l%$: %v");
  spdlog::set_level(level);
}

}  // namespace deepnav
