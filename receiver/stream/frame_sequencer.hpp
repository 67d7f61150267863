#pragma once
// Puts the frames of a datagram stream back in order by sequence number. A frame that
// arrives early waits for the ones before it; a missing number is declared lost once a
// frame `window` or more numbers after it has come (each missing number has its own
// window: a frame held back just after a lost one is still in time), or the stream ends. So every
// frame is classified exactly once: delivered (in order, possibly after reordering),
// duplicated, late (arrived after being declared lost) or lost.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "receiver/stream/stream_protocol.hpp"

namespace deepnav {

class FrameSequencer {
 public:
  using Deliver = std::function<void(stream::Frame&&)>;
  /// `on_lost` gets each run of lost sequence numbers as [first, last] (adjacent runs
  /// declared at different times are reported as one, once a frame or the end closes it).
  using Lost = std::function<void(std::uint64_t first, std::uint64_t last)>;

  FrameSequencer(std::size_t window, Deliver deliver, Lost on_lost);

  /// Starts a new session whose sequence numbers begin at `first_sequence`; whatever is
  /// still waiting is flushed first.
  void restart(std::uint64_t first_sequence);
  void add(stream::Frame frame);
  /// The stream ended: frames still waiting are delivered, the holes before them lost.
  void flush();
  /// The stream ended with the end-of-stream frame numbered `end_sequence`: as flush(), and
  /// the numbers after the last frame that came, up to it, are lost too.
  void finish(std::uint64_t end_sequence);

  std::int64_t duplicated() const { return duplicated_; }
  std::int64_t reordered() const { return reordered_; }
  std::int64_t late() const { return late_; }
  std::int64_t lost() const { return lost_; }
  std::uint64_t next_sequence() const { return next_; }

 private:
  void deliver_ready();
  void declare_lost_until(std::uint64_t sequence);
  void report_pending_lost();

  std::size_t window_;
  Deliver deliver_;
  Lost on_lost_;
  std::uint64_t next_ = 0;  ///< the sequence number delivered next
  std::uint64_t max_seen_ = 0;
  bool any_seen_ = false;
  std::map<std::uint64_t, stream::Frame> waiting_;
  std::set<std::uint64_t> recently_lost_;  ///< to tell a late frame from a duplicate (bounded)
  std::optional<std::pair<std::uint64_t, std::uint64_t>> pending_lost_;  ///< declared, not yet reported
  std::int64_t duplicated_ = 0, reordered_ = 0, late_ = 0, lost_ = 0;
};

}  // namespace deepnav
