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
#include <cstdint>
#include <deque>
#include <vector>

namespace deepnav {

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
  /// The pieces, oldest first, that arrived at least horizon_s before `now_s` (all of them
  /// when `flush`: the stream ended), with the samples missing before each.
  std::vector<Verdict> release(double now_s, bool flush = false);

  /// The consumer fell behind at `now_s` (it held the producer up): forget the baseline and
  /// judge no piece that arrived before now_s + horizon_s.
  void backlogged(double now_s);

  std::int64_t declared_lost() const { return declared_; }
  std::size_t held_pieces() const { return held_.size(); }

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
  std::deque<Piece> held_;
  std::deque<Baseline> baseline_;  ///< increasing lag from front to back: the front is the minimum
};

}  // namespace deepnav
