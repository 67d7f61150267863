#pragma once
// Watches how many of the filter's measurement rows the innovation gate turns away. A
// filter whose own state has gone wrong (an IMU far outside its grade, a steered channel
// pulled off its signal) can keep a healthy-looking covariance while most measurements
// fail the gate; this is what tells the receiver to restart it. Fed with the range updates
// (tight, ultra-tight), one row per satellite measurement.
#include <deque>

#include "ins/kalman_filter.hpp"

namespace deepnav::aiding {

struct InnovationMonitorConfig {
  double window_s = 3.0;               ///< judged over the updates of the last window_s
  int min_rows = 15;                   ///< fewer rows than this say nothing
  double max_rejected_fraction = 0.2;  ///< more rejected than this: inconsistent (a 5-sigma gate rejects almost none)
};

class InnovationMonitor {
 public:
  explicit InnovationMonitor(InnovationMonitorConfig config = {}) : cfg_(config) {}

  /// One filter update at time t_s (non-decreasing).
  void add(double t_s, const KalmanUpdate& update);
  /// Whether, over the window ending at the last update, the gate rejected more than the
  /// allowed fraction of at least min_rows rows.
  bool inconsistent() const;
  int rows() const { return rows_; }
  int rejected() const { return rejected_; }
  void clear();

 private:
  struct Entry {
    double t_s;
    int rows, rejected;
  };
  InnovationMonitorConfig cfg_;
  std::deque<Entry> entries_;
  int rows_ = 0, rejected_ = 0;
};

}  // namespace deepnav::aiding
