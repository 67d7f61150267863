#include "tools/cli/stop_signals.hpp"

#include <csignal>
#include <cstdlib>

namespace deepnav::cli {
namespace {

std::atomic<bool> g_stop{false};
using Handler = void (*)(int);
Handler g_previous_int = SIG_DFL, g_previous_term = SIG_DFL;

extern "C" void on_stop_signal(int) {
  if (g_stop.load()) std::_Exit(130);  // a second Ctrl-C: the user does not want to wait
  g_stop.store(true);
}

}  // namespace

StopOnSignals::StopOnSignals() {
  g_stop = false;
  g_previous_int = std::signal(SIGINT, on_stop_signal);
  g_previous_term = std::signal(SIGTERM, on_stop_signal);
}

StopOnSignals::~StopOnSignals() {
  std::signal(SIGINT, g_previous_int);
  std::signal(SIGTERM, g_previous_term);
}

const std::atomic<bool>& StopOnSignals::flag() const { return g_stop; }

}  // namespace deepnav::cli
