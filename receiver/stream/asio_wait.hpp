#pragma once
// Synchronous-looking Boost.Asio operations with a deadline and a cancel flag: start an
// asynchronous operation whose handler sets `done`, then run the io_context until it
// has, the deadline passes or `cancel` is set (then `abort` cancels the operation and the
// handler still runs, with operation_aborted, before this returns).
#include <fmt/format.h>

#include <atomic>
#include <boost/asio/buffer.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstddef>
#include <string>
#include <thread>
#include <vector>

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

/// The time point `seconds` from now.
inline Clock::time_point after(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

/// Reads what `socket` has, up to buffer.size() bytes. Returns the bytes read, or 0 with
/// `why` set when nothing came for `idle_timeout_s`, `cancel` was set, the peer closed the
/// connection or the read failed (the socket is closed on a timeout or a cancel).
template <typename Socket>
std::size_t read_some(boost::asio::io_context& io, Socket& socket, std::vector<std::byte>& buffer,
                      double idle_timeout_s, const std::atomic<bool>& cancel, std::string& why) {
  bool done = false;
  boost::system::error_code ec;
  std::size_t got = 0;
  socket.async_read_some(boost::asio::buffer(buffer), [&](const boost::system::error_code& e, std::size_t n) {
    ec = e;
    got = n;
    done = true;
  });
  if (!run_until_done(io, done, after(idle_timeout_s), cancel, [&] { socket.close(); })) {
    why = cancel.load() ? "interrupted" : fmt::format("nothing received for {} s", idle_timeout_s);
    return 0;
  }
  if (ec) {
    why = ec == boost::asio::error::eof ? "the server closed the connection" : ec.message();
    return 0;
  }
  return got;
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
