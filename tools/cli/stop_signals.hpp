#pragma once
// Ctrl-C (SIGINT), SIGTERM and a hangup (SIGHUP: the terminal or ssh session is gone) stop
// a long-running command cleanly: its products are closed and its summary says it was
// interrupted. The command then exits with 128 + the signal's number (130, 143, 129), as a
// shell reports a process the signal ended, so a script can tell an interrupted run from a
// complete one.
#include <atomic>
#include <string>

namespace deepnav::cli {

/// SIGINT/SIGTERM/SIGHUP set the returned flag while the guard lives (the previous handlers
/// are restored after); a second signal while stopping exits at once with 128 + its number.
/// After SIGHUP, SIGPIPE is ignored: writing to the lost terminal then fails instead of
/// ending the process before its products are closed.
class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;
  const std::atomic<bool>& flag() const;
  /// The first signal received (0: none).
  int signal() const;
};

/// The exit status of a command a signal stopped: 128 + its number.
int interrupted_exit_status(int signal);
/// "SIGINT", "SIGTERM", "SIGHUP" (else "signal N").
std::string signal_name(int signal);

}  // namespace deepnav::cli
