#include "receiver/stream/stream_sample_queue.hpp"

#include <algorithm>

namespace deepnav {

bool StreamSampleQueue::push(StreamPiece piece, const std::atomic<bool>& cancel) {
  std::unique_lock lock(mutex_);
  // A piece larger than the whole capacity is still accepted into an empty queue.
  while (!pieces_.empty() && bytes_ + piece.raw.size() > capacity_) {
    if (cancel.load()) return false;
    changed_.wait_for(lock, std::chrono::milliseconds(50));
  }
  if (cancel.load()) return false;
  bytes_ += piece.raw.size();
  peak_ = std::max(peak_, bytes_);
  pieces_.push_back(std::move(piece));
  changed_.notify_all();
  return true;
}

bool StreamSampleQueue::try_push(StreamPiece piece) {
  std::lock_guard lock(mutex_);
  if (!pieces_.empty() && bytes_ + piece.raw.size() > capacity_) return false;
  bytes_ += piece.raw.size();
  peak_ = std::max(peak_, bytes_);
  pieces_.push_back(std::move(piece));
  changed_.notify_all();
  return true;
}

void StreamSampleQueue::finish(StreamEnd end) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  end_ = std::move(end);
  changed_.notify_all();
}

StreamSampleQueue::PopResult StreamSampleQueue::pop(StreamPiece& out, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  if (!changed_.wait_for(lock, timeout, [&] { return !pieces_.empty() || finished_; })) return PopResult::timeout;
  if (pieces_.empty()) return PopResult::end;
  out = std::move(pieces_.front());
  pieces_.pop_front();
  bytes_ -= out.raw.size();
  changed_.notify_all();
  return PopResult::piece;
}

StreamEnd StreamSampleQueue::end() const {
  std::lock_guard lock(mutex_);
  return end_;
}

std::size_t StreamSampleQueue::queued_bytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

std::size_t StreamSampleQueue::peak_bytes() const {
  std::lock_guard lock(mutex_);
  return peak_;
}

}  // namespace deepnav
