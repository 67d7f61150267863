#pragma once
// Lost samples in a stream that carries no indices (rtl_tcp: bare cu8 bytes), told from
// arrival times. The dongle makes samples at the sample rate in real time; an rtl_tcp
// server that cannot send fast enough, or a USB overrun, drops whole buffers, and the
// samples after the hole then arrive as late as the hole was long, and stay so. Data that
// is merely delayed (a scheduling hiccup, TCP retransmission) arrives late too but catches
// up in a burst.
//
// For every piece the lag is fs * (arrival time - first arrival) - samples received; its
// low envelope is the transport's smallest latency. A piece is judged once `horizon_s` of
// arrivals after it are known: the smallest lag of it and everything after it (the floor)
// is compared with the smallest lag of the pieces released in the last `baseline_s` (the
// baseline, each less the losses declared before it). A floor above the baseline by more
// than `threshold_s` means samples were lost just before the piece: that many are declared,
// and the piece's samples get indices after the hole. A delay does not raise the floor
// (the burst after it brings the lag back down within the horizon); a sample clock that
// differs from the host's by ppm moves the baseline with it. A loss shorter than the
// threshold is not seen, and its size is known to the timing jitter (a few ms on a quiet
// link). While the consumer falls behind (backlogged()), arrival times say when it read, not
// when the dongle sampled: pieces that arrived up to a horizon after that are not judged,
// and a new baseline is built from the pieces after them (a loss meanwhile goes uncounted).
//
// All of that holds for a sender that keeps real time. One that sends slower (a file
// replayed slowly, a link narrower than the rate) makes every piece later than the one
// before: its lag grows steadily, which is no loss, and arrival times then cannot tell a
// loss at all (rtl_tcp has no sample indices). So the pace of the arrivals is measured
// (arrival_pace.hpp); while it is below kSlowPace the stream is slow: no piece gets a
// verdict and the baseline is dropped, to be rebuilt once the pace is back. Until the pace
// is known (2 s of arrivals, at the start and after a backlog) pieces are held; a stream
// that ends before leaves its pieces unjudged.
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "receiver/stream/arrival_pace.hpp"

namespace deepnav {

/// A stream arriving at less than this fraction of its sample rate is a slow sender, not
/// a lossy one (far below what a dongle's clock, a few ppm off, or jitter can do).
inline constexpr double kSlowPace = 0.95;

class ArrivalLossDetector {
 public:
  ArrivalLossDetector(double sample_rate_hz, double threshold_s = 0.025, double horizon_s = 1.0,
                      double baseline_s = 10.0);

  /// A piece of `count` samples arrived at `t_s` (a monotonic clock, seconds).
  void arrived(double t_s, std::int64_t count);

  struct Verdict {
    std::int64_t count = 0;           ///< the piece's samples
    std::int64_t missing_before = 0;  ///< samples lost just before it (0: none)
  };
  /// The pieces, oldest first, that arrived at least horizon_s before `now_s`, once the pace
  /// is known (all of them when `flush`: the stream ended), with the samples missing before
  /// each.
  std::vector<Verdict> release(double now_s, bool flush = false);

  /// The consumer fell behind at `now_s` (it held the producer up): forget the baseline and
  /// judge no piece that arrived before now_s + horizon_s.
  void backlogged(double now_s);

  std::int64_t declared_lost() const { return declared_; }
  std::size_t held_pieces() const { return held_.size(); }
  /// Whether the last release() found the stream slower than kSlowPace.
  bool slow() const { return slow_; }
  const ArrivalPace& pace() const { return pace_; }

 private:
  struct Piece {
    double t_s;
    std::int64_t count;
    double lag;  ///< samples, before any loss is declared
  };
  struct Baseline {
    double t_s;
    double lag;  ///< less the losses declared before it
  };
  double fs_, threshold_samples_, horizon_s_, baseline_s_;
  bool started_ = false;
  double t0_ = 0.0;
  std::int64_t received_ = 0;
  std::int64_t declared_ = 0;
  double quiet_until_s_ = -1e300;
  ArrivalPace pace_;
  bool slow_ = false;
  std::deque<Piece> held_;
  std::deque<Baseline> baseline_;  ///< increasing lag from front to back: the front is the minimum
};

}  // namespace deepnav
