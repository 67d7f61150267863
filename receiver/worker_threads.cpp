#include "receiver/worker_threads.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <latch>
#include <stdexcept>
#include <system_error>

namespace deepnav {
namespace {

constexpr std::chrono::microseconds kSpin{200};  ///< how long an idle worker watches the queue before it sleeps

}  // namespace

WorkerThreads::WorkerThreads(std::size_t count, const char* what) {
  threads_.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    try {
      threads_.emplace_back([this] { work(); });
    } catch (const std::system_error& e) {
      const std::size_t started = threads_.size();
      stop_and_join();
      throw std::runtime_error(
          fmt::format("cannot start {} thread {} of {} ({} started): {}", what, i + 1, count, started, e.what()));
    }
  }
}

WorkerThreads::~WorkerThreads() { stop_and_join(); }

void WorkerThreads::stop_and_join() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_)
    if (t.joinable()) t.join();
  threads_.clear();
}

void WorkerThreads::post(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    tasks_.push_back(std::move(task));
    queued_.store(tasks_.size(), std::memory_order_release);
  }
  wake_.notify_one();
}

void WorkerThreads::work() {
  while (true) {
    std::function<void()> task;
    // The receiver hands each worker a share of a 10 ms block, about 0.1 ms of work, and the
    // next one shortly after: waking from the condition variable took as long as the work
    // (two threads ran slower than one). A worker first watches the queue for a while.
    const auto spin_until = std::chrono::steady_clock::now() + kSpin;
    while (queued_.load(std::memory_order_acquire) == 0 && std::chrono::steady_clock::now() < spin_until) {
    }
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
      if (tasks_.empty()) return;  // stopping, and nothing left to do
      task = std::move(tasks_.front());
      tasks_.pop_front();
      queued_.store(tasks_.size(), std::memory_order_release);
    }
    task();
  }
}

void run_in_shares(WorkerThreads* workers, std::size_t n, const std::function<void(std::size_t)>& work) {
  if (!workers || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) work(i);
    return;
  }
  const std::size_t shares = std::min(workers->size() + 1, n);
  const auto share = [&](std::size_t g) {
    for (std::size_t i = g * n / shares; i < (g + 1) * n / shares; ++i) work(i);
  };
  std::latch done(static_cast<std::ptrdiff_t>(shares - 1));
  std::vector<std::exception_ptr> errors(shares);
  for (std::size_t g = 1; g < shares; ++g) {
    workers->post([&, g] {
      try {
        share(g);
      } catch (...) {
        errors[g] = std::current_exception();
      }
      done.count_down();
    });
  }
  try {
    share(0);
  } catch (...) {
    errors[0] = std::current_exception();
  }
  done.wait();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace deepnav
