#pragma once
// Ctrl-C and SIGTERM stop a long-running command cleanly: its products are closed and its
// summary says it was interrupted.
#include <atomic>

namespace deepnav::cli {

/// SIGINT/SIGTERM set the returned flag while the guard lives (the previous handlers
/// are restored after); a second signal while stopping exits at once.
class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;
  const std::atomic<bool>& flag() const;
};

}  // namespace deepnav::cli
