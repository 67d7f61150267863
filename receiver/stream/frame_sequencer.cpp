#include "receiver/stream/frame_sequencer.hpp"

#include <algorithm>

namespace deepnav {
namespace {
constexpr std::size_t kLostMemory = 4096;
}

FrameSequencer::FrameSequencer(std::size_t window, Deliver deliver, Lost on_lost)
    : window_(window == 0 ? 1 : window), deliver_(std::move(deliver)), on_lost_(std::move(on_lost)) {}

void FrameSequencer::restart(std::uint64_t first_sequence) {
  flush();
  next_ = first_sequence;
  recently_lost_.clear();
  any_seen_ = false;
}

void FrameSequencer::add(stream::Frame frame) {
  const std::uint64_t seq = frame.header.sequence;
  if (seq < next_) {
    if (recently_lost_.erase(seq) > 0) {
      ++late_;
    } else {
      ++duplicated_;
    }
    return;
  }
  if (waiting_.count(seq) > 0) {
    ++duplicated_;
    return;
  }
  // Out of order: a later frame came first (this one is still in time to be used).
  if (any_seen_ && seq < max_seen_) ++reordered_;
  if (!any_seen_ || seq > max_seen_) max_seen_ = seq;
  any_seen_ = true;
  waiting_.emplace(seq, std::move(frame));
  deliver_ready();
  // Missing numbers `window` or more behind the newest frame are not coming; the ones
  // after them still have time.
  while (!waiting_.empty() && waiting_.rbegin()->first - next_ >= window_) {
    declare_lost_until(std::min(waiting_.begin()->first, waiting_.rbegin()->first - window_ + 1));
    deliver_ready();
  }
}

void FrameSequencer::flush() {
  while (!waiting_.empty()) {
    declare_lost_until(waiting_.begin()->first);
    deliver_ready();
  }
  report_pending_lost();
}

void FrameSequencer::finish(std::uint64_t end_sequence) {
  flush();
  declare_lost_until(end_sequence);
  report_pending_lost();
}

void FrameSequencer::report_pending_lost() {
  if (!pending_lost_) return;
  on_lost_(pending_lost_->first, pending_lost_->second);
  pending_lost_.reset();
}

void FrameSequencer::deliver_ready() {
  for (auto it = waiting_.begin(); it != waiting_.end() && it->first == next_; it = waiting_.begin()) {
    report_pending_lost();  // a delivered frame ends the run of lost numbers before it
    stream::Frame f = std::move(it->second);
    waiting_.erase(it);
    ++next_;
    deliver_(std::move(f));
  }
}

void FrameSequencer::declare_lost_until(std::uint64_t sequence) {
  if (sequence <= next_) return;
  if (pending_lost_ && pending_lost_->second + 1 == next_) pending_lost_->second = sequence - 1;
  else {
    report_pending_lost();
    pending_lost_ = {next_, sequence - 1};
  }
  lost_ += static_cast<std::int64_t>(sequence - next_);
  // Only the last kLostMemory numbers can be remembered: start there, so a long run of
  // losses costs that many steps at most, not one per lost number.
  const std::uint64_t from = sequence - next_ > kLostMemory ? sequence - kLostMemory : next_;
  for (std::uint64_t s = from; s < sequence; ++s) {
    recently_lost_.insert(s);
    if (recently_lost_.size() > kLostMemory) recently_lost_.erase(recently_lost_.begin());
  }
  next_ = sequence;
}

}  // namespace deepnav
