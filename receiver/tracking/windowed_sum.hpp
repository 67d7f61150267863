#pragma once
// Sum over the last N values pushed, in O(1) per value: the lock detectors ask for their
// windows' sums after every epoch (up to 2000 values each at 1 ms integrations).
#include <cstddef>
#include <deque>
#include <numeric>

namespace deepnav {

class WindowedSum {
 public:
  /// Adds v, then drops the oldest values until at most `capacity` remain.
  void push(double v, std::size_t capacity) {
    values_.push_back(v);
    sum_ += v;
    while (values_.size() > capacity) {
      sum_ -= values_.front();
      values_.pop_front();
      // Adding and subtracting leaves rounding residue behind; a fresh sum now and then
      // keeps it at the level of one window's rounding.
      if (++drops_ >= kResum) resum();
    }
  }
  void clear() {
    values_.clear();
    sum_ = 0.0;
    drops_ = 0;
  }
  double sum() const { return sum_; }
  double mean() const { return values_.empty() ? 0.0 : sum_ / static_cast<double>(values_.size()); }
  std::size_t size() const { return values_.size(); }
  bool empty() const { return values_.empty(); }

 private:
  static constexpr int kResum = 4096;
  void resum() {
    sum_ = std::accumulate(values_.begin(), values_.end(), 0.0);
    drops_ = 0;
  }
  std::deque<double> values_;
  double sum_ = 0.0;
  int drops_ = 0;
};

}  // namespace deepnav
