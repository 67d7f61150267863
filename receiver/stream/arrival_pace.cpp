#include "receiver/stream/arrival_pace.hpp"

#include <algorithm>
#include <vector>

namespace deepnav {

ArrivalPace::ArrivalPace(double sample_rate_hz, double window_s, double segment_s, int min_segments)
    : fs_(sample_rate_hz), window_s_(window_s), segment_s_(segment_s), min_segments_(min_segments) {}

void ArrivalPace::arrived(double t_s, std::int64_t count) {
  if (!started_) {
    started_ = true;
    first_t_s_ = t_s;
    first_count_ = count;
  }
  last_t_s_ = t_s;
  total_ += count;
  arrivals_.push_back({t_s, count});
  // A trickle keeps its last few pieces however old, so that its pace is known at all.
  const auto keep = static_cast<std::size_t>(min_segments_) + 1;
  while (arrivals_.size() > keep && arrivals_[1].t_s <= t_s - window_s_) arrivals_.pop_front();
}

void ArrivalPace::restart() { arrivals_.clear(); }

std::optional<double> ArrivalPace::median() const {
  std::vector<double> rates;
  std::size_t a = 0;
  while (a < arrivals_.size()) {
    std::int64_t samples = 0;
    std::size_t b = a + 1;
    for (; b < arrivals_.size(); ++b) {
      samples += arrivals_[b].count;  // the pieces after the segment's first: sent during it
      if (arrivals_[b].t_s - arrivals_[a].t_s >= segment_s_) break;
    }
    if (b >= arrivals_.size()) break;  // the last, unfinished segment
    rates.push_back(static_cast<double>(samples) / (fs_ * (arrivals_[b].t_s - arrivals_[a].t_s)));
    a = b;
  }
  if (rates.size() < static_cast<std::size_t>(min_segments_)) return std::nullopt;
  const auto mid = rates.begin() + static_cast<std::ptrdiff_t>(rates.size() / 2);
  std::nth_element(rates.begin(), mid, rates.end());
  return *mid;
}

std::optional<double> ArrivalPace::mean() const {
  if (!median()) return std::nullopt;
  std::int64_t samples = 0;
  for (std::size_t i = 1; i < arrivals_.size(); ++i) samples += arrivals_[i].count;
  return static_cast<double>(samples) / (fs_ * (arrivals_.back().t_s - arrivals_.front().t_s));
}

std::optional<double> ArrivalPace::overall() const {
  if (!(last_t_s_ > first_t_s_)) return std::nullopt;
  return static_cast<double>(total_ - first_count_) / (fs_ * (last_t_s_ - first_t_s_));
}

}  // namespace deepnav
