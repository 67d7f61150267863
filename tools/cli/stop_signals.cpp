#include "tools/cli/stop_signals.hpp"

#include <csignal>
#include <cstdlib>
#include <string>

namespace deepnav::cli {
namespace {

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
struct sigaction g_previous[std::size(kStopSignals)];

extern "C" void on_stop_signal(int signal) {
  // A second signal: the user does not want to wait.
  if (g_stop.load()) std::_Exit(interrupted_exit_status(signal));
  if (signal == SIGHUP) std::signal(SIGPIPE, SIG_IGN);
  g_signal.store(signal);
  g_stop.store(true);
}

}  // namespace

StopOnSignals::StopOnSignals() {
  g_stop = false;
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a blocking read or write goes on; the flag is polled
  for (std::size_t i = 0; i < std::size(kStopSignals); ++i) sigaction(kStopSignals[i], &action, &g_previous[i]);
}

StopOnSignals::~StopOnSignals() {
  for (std::size_t i = 0; i < std::size(kStopSignals); ++i) sigaction(kStopSignals[i], &g_previous[i], nullptr);
}

const std::atomic<bool>& StopOnSignals::flag() const { return g_stop; }

int StopOnSignals::signal() const { return g_signal.load(); }

int interrupted_exit_status(int signal) { return 128 + signal; }

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal " + std::to_string(signal);
  }
}

}  // namespace deepnav::cli
