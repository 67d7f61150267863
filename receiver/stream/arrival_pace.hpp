#pragma once
// How fast a stream without sample indices (rtl_tcp) delivers, as a fraction of its sample
// rate, told from arrival times. A dongle makes samples in real time; a server replaying a
// file, or one behind a link slower than the rate, sends them slower, and then arrival
// times cannot tell lost samples from late ones (every piece arrives later than the one
// before it would have in real time). The pace is measured over the last `window_s` of
// arrivals, cut into segments of at least `segment_s` that start and end on a piece (so a
// sender's buffer size does not quantize it): the median of the segments' rates, so that
// a hole (samples dropped) or a stall and the burst after it sway a segment or two and not
// the measure. It is known once there are `min_segments` segments.
#include <cstdint>
#include <deque>
#include <optional>

namespace deepnav {

class ArrivalPace {
 public:
  explicit ArrivalPace(double sample_rate_hz, double window_s = 4.0, double segment_s = 0.5, int min_segments = 4);

  /// A piece of `count` samples arrived at `t_s` (a monotonic clock, seconds).
  void arrived(double t_s, std::int64_t count);
  /// Forgets the arrivals so far (their times said when the consumer read, not when the
  /// sender sent); the whole-stream figures stay.
  void restart();

  /// The median segment rate over the window as a fraction of the sample rate (1: real
  /// time), once known.
  std::optional<double> median() const;
  /// Samples per second over the window (first piece to last) as a fraction of the sample
  /// rate, once median() is known: the figure to report, as a trickle's median may be 0.
  std::optional<double> mean() const;
  /// Over the whole stream, first piece to last; nullopt before two arrival times differ.
  std::optional<double> overall() const;

 private:
  struct Arrival {
    double t_s;
    std::int64_t count;
  };
  double fs_, window_s_, segment_s_;
  int min_segments_;
  std::deque<Arrival> arrivals_;  ///< the window's, and never fewer than min_segments + 1
  bool started_ = false;
  double first_t_s_ = 0.0, last_t_s_ = 0.0;
  std::int64_t first_count_ = 0, total_ = 0;
};

}  // namespace deepnav
