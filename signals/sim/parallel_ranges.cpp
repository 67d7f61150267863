#include "signals/sim/parallel_ranges.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <vector>

namespace deepnav {

unsigned resolved_threads(unsigned threads) {
  return threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
}

int range_workers(unsigned threads, int total) {
  return static_cast<int>(std::min<unsigned>(std::max(1u, threads), static_cast<unsigned>(std::max(1, total))));
}

void run_in_ranges(unsigned threads, int total, const std::function<void(int, int, int)>& body) {
  if (total <= 0) return;
  const int workers = range_workers(threads, total);
  if (workers == 1) {
    body(0, 0, total);
    return;
  }
  // Never std::terminate: a worker's exception ends the call with an error once every
  // started worker has been joined.
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  std::vector<std::thread> pool;
  std::exception_ptr start_error;
  for (int w = 1; w < workers; ++w) {
    try {
      pool.emplace_back([&, w] {
        try {
          body(w, range_begin(total, workers, w), range_begin(total, workers, w + 1));
        } catch (...) {
          errors[static_cast<std::size_t>(w)] = std::current_exception();
        }
      });
    } catch (const std::system_error& e) {
      start_error = std::make_exception_ptr(
          std::runtime_error(fmt::format("cannot start synthesis thread {} of {}: {}", w + 1, workers, e.what())));
      break;
    }
  }
  if (!start_error) {
    try {
      body(0, 0, range_begin(total, workers, 1));
    } catch (...) {
      errors[0] = std::current_exception();
    }
  }
  for (auto& t : pool) t.join();
  if (start_error) std::rethrow_exception(start_error);
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace deepnav
