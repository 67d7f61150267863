#include "receiver/worker_threads.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <system_error>

namespace deepnav {

WorkerThreads::WorkerThreads(std::size_t count, const char* what) {
  threads_.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    try {
      threads_.emplace_back([this] { work(); });
    } catch (const std::system_error& e) {
      const std::size_t started = threads_.size();
      stop_and_join();
      throw std::runtime_error(fmt::format("cannot start {} thread {} of {} ({} started): {}", what, i + 1, count,
                                           started, e.what()));
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
  }
  wake_.notify_one();
}

void WorkerThreads::work() {
  while (true) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
      if (tasks_.empty()) return;  // stopping, and nothing left to do
      task = std::move(tasks_.front());
      tasks_.pop_front();
    }
    task();
  }
}

}  // namespace deepnav
