#include "receiver/stream/arrival_loss_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepnav {

ArrivalLossDetector::ArrivalLossDetector(double sample_rate_hz, double threshold_s, double horizon_s, double baseline_s)
    : fs_(sample_rate_hz),
      threshold_samples_(threshold_s * sample_rate_hz),
      horizon_s_(horizon_s),
      baseline_s_(baseline_s),
      pace_(sample_rate_hz) {}

void ArrivalLossDetector::arrived(double t_s, std::int64_t count) {
  if (!started_) {
    started_ = true;
    t0_ = t_s;
  }
  received_ += count;
  pace_.arrived(t_s, count);
  held_.push_back({t_s, count, fs_ * (t_s - t0_) - static_cast<double>(received_)});
}

void ArrivalLossDetector::backlogged(double now_s) {
  baseline_.clear();
  pace_.restart();
  quiet_until_s_ = now_s + horizon_s_;
}

std::vector<ArrivalLossDetector::Verdict> ArrivalLossDetector::release(double now_s, bool flush) {
  std::vector<Verdict> out;
  const std::optional<double> pace = pace_.median();
  // Until the pace is known, a lag that grows may be a loss or a slow sender: the pieces wait
  // (at the end of a stream too short to tell, they go unjudged).
  if (!pace && !flush) return out;
  slow_ = pace && *pace < kSlowPace;
  if (slow_) baseline_.clear();  // lags that grow with a slow sender are no baseline
  while (!held_.empty() && (flush || held_.front().t_s + horizon_s_ <= now_s)) {
    double floor = std::numeric_limits<double>::infinity();
    for (const Piece& p : held_) floor = std::min(floor, p.lag);
    floor -= static_cast<double>(declared_);
    const Piece piece = held_.front();
    held_.pop_front();
    Verdict v{piece.count, 0};
    if (piece.t_s <= quiet_until_s_) {
      out.push_back(v);  // its arrival time says nothing: no verdict, no part in the baseline
      continue;
    }
    if (slow_ || !pace) {
      out.push_back(v);  // late because the sender is slow, or no telling: no verdict
      continue;
    }
    if (!baseline_.empty()) {
      const double base = baseline_.front().lag;
      if (floor - base > threshold_samples_) {
        v.missing_before = std::llround(floor - base);
        declared_ += v.missing_before;
      }
    }
    // Sliding minimum of the adjusted lags over the last baseline_s.
    const double adjusted = piece.lag - static_cast<double>(declared_);
    while (!baseline_.empty() && baseline_.back().lag >= adjusted) baseline_.pop_back();
    baseline_.push_back({piece.t_s, adjusted});
    while (baseline_.front().t_s < piece.t_s - baseline_s_) baseline_.pop_front();
    out.push_back(v);
  }
  return out;
}

}  // namespace deepnav
