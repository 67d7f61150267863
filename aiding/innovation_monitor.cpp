#include "aiding/innovation_monitor.hpp"

namespace deepnav::aiding {

void InnovationMonitor::add(double t_s, const KalmanUpdate& update) {
  if (update.rows == 0) return;
  entries_.push_back({t_s, update.rows, update.rejected});
  rows_ += update.rows;
  rejected_ += update.rejected;
  while (!entries_.empty() && entries_.front().t_s <= t_s - cfg_.window_s) {
    rows_ -= entries_.front().rows;
    rejected_ -= entries_.front().rejected;
    entries_.pop_front();
  }
}

bool InnovationMonitor::inconsistent() const {
  return rows_ >= cfg_.min_rows && rejected_ > cfg_.max_rejected_fraction * rows_;
}

void InnovationMonitor::clear() {
  entries_.clear();
  rows_ = rejected_ = 0;
}

}  // namespace deepnav::aiding
