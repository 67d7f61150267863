#pragma once
// The hand-over between a network source's I/O thread (producer) and the receiver
// (consumer): pieces of raw sample bytes tagged with the absolute index of their first
// sample, bounded in bytes, then one end marker with the reason the stream ended.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace deepnav {

struct StreamPiece {
  std::int64_t first_sample_index = 0;
  std::vector<std::byte> raw;  ///< whole samples in the stream's format
};

/// How a stream ended: `failed` for a protocol violation or a connection that could not
/// be re-established (the message says which), otherwise a normal end.
struct StreamEnd {
  StreamEnd() = default;
  StreamEnd(std::string why, bool failed_, std::optional<std::int64_t> end_index = std::nullopt)
      : reason(std::move(why)), failed(failed_), end_sample_index(end_index) {}
  std::string reason;
  bool failed = false;
  /// One past the stream's last sample, when the end says so (the end-of-stream frame's
  /// first sample index): samples missing before it are a gap like any other.
  std::optional<std::int64_t> end_sample_index;
};

class StreamSampleQueue {
 public:
  explicit StreamSampleQueue(std::size_t capacity_bytes) : capacity_(capacity_bytes) {}

  /// Waits while the queue is full (TCP backpressure: the producer stops reading its
  /// socket); returns false, dropping the piece, once `cancel` is set.
  bool push(StreamPiece piece, const std::atomic<bool>& cancel);
  /// Never waits: false (piece dropped) when the queue is full (UDP overrun).
  bool try_push(StreamPiece piece);
  /// No more pieces will come; the consumer sees `end` after the queued ones.
  void finish(StreamEnd end);

  enum class PopResult { piece, timeout, end };
  /// Waits up to `timeout` for the next piece.
  PopResult pop(StreamPiece& out, std::chrono::milliseconds timeout);
  /// The end marker (valid once pop() returned PopResult::end).
  StreamEnd end() const;
  std::size_t queued_bytes() const;
  std::size_t peak_bytes() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<StreamPiece> pieces_;
  std::size_t capacity_;
  std::size_t bytes_ = 0, peak_ = 0;
  bool finished_ = false;
  StreamEnd end_;
};

}  // namespace deepnav
