#pragma once
// A fixed set of worker threads taking posted tasks in order. Unlike a pool that starts
// its threads inside a constructor it cannot unwind from, a thread that cannot be created
// (a process or memory limit) is an error naming how many were asked for and how many
// started: the threads already started are stopped and joined first, so nothing hangs.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace deepnav {

class WorkerThreads {
 public:
  /// Starts `count` threads; throws std::runtime_error, naming `what` (e.g. "channel
  /// worker"), when one cannot be created.
  WorkerThreads(std::size_t count, const char* what);
  /// Finishes the tasks already posted, then joins every thread.
  ~WorkerThreads();
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;

  /// Queues a task for the next free thread. Tasks must not throw (catch inside).
  void post(std::function<void()> task);
  std::size_t size() const { return threads_.size(); }

 private:
  void work();
  void stop_and_join();

  std::atomic<std::size_t> queued_{0};  ///< tasks_.size(), readable without the lock
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

/// Runs work(i) for every i in [0, n), in one contiguous share per thread: the calling
/// thread takes the first share and `workers` (nullptr: none, the calling thread does all)
/// the others. One hand-off per thread rather than per item: the receiver's items (a channel
/// over a 10 ms block) take about 0.1 ms each. Returns when every share is done; then
/// rethrows the exception of the first share that threw (a share stops at its first).
void run_in_shares(WorkerThreads* workers, std::size_t n, const std::function<void(std::size_t)>& work);

}  // namespace deepnav
