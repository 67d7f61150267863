#pragma once
// Synchronous-looking Boost.Asio operations with a deadline and a cancel flag: start an
// asynchronous operation whose handler sets `done`, then run the io_context until it
// has, the deadline passes or `cancel` is set (then `abort` cancels the operation and the
// handler still runs, with operation_aborted, before this returns).
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <thread>

namespace deepnav::asio_wait {

using Clock = std::chrono::steady_clock;

/// True when the operation completed by itself (its handler's error code says how).
template <typename Abort>
bool run_until_done(boost::asio::io_context& io, const bool& done, Clock::time_point deadline,
                    const std::atomic<bool>& cancel, Abort&& abort) {
  io.restart();
  while (!done) {
    const auto now = Clock::now();
    if (cancel.load() || now >= deadline) {
      abort();
      while (!done) {
        io.restart();
        io.run_for(std::chrono::milliseconds(10));
      }
      return false;
    }
    const auto slice = std::min<Clock::duration>(deadline - now, std::chrono::milliseconds(50));
    io.run_for(slice);
    if (io.stopped() && !done) io.restart();
  }
  return true;
}

/// Sleeps until `until` in short slices; false when `cancel` was set first.
inline bool sleep_until(Clock::time_point until, const std::atomic<bool>& cancel) {
  while (Clock::now() < until) {
    if (cancel.load()) return false;
    std::this_thread::sleep_for(std::min<Clock::duration>(until - Clock::now(), std::chrono::milliseconds(50)));
  }
  return !cancel.load();
}

}  // namespace deepnav::asio_wait
