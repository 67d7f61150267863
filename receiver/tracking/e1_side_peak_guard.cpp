#include "receiver/tracking/e1_side_peak_guard.hpp"

#include <algorithm>
#include <stdexcept>

namespace deepnav {

SidePeakGuard::SidePeakGuard(int threshold, int max_jumps) : threshold_(threshold), max_jumps_(max_jumps) {
  if (threshold < 1) throw std::invalid_argument("E1 side-peak guard: the threshold must be at least 1");
  if (max_jumps < 0) throw std::invalid_argument("E1 side-peak guard: max_jumps must be >= 0");
}

double SidePeakGuard::add(const std::complex<double>& ve, const std::complex<double>& p,
                          const std::complex<double>& vl) {
  const double e = std::abs(ve), m = std::abs(p), l = std::abs(vl);
  const bool early_wins = e > m && e >= l;
  const bool late_wins = l > m && l > e;
  early_count_ = early_wins ? early_count_ + 1 : std::max(0, early_count_ - 1);
  late_count_ = late_wins ? late_count_ + 1 : std::max(0, late_count_ - 1);
  double jump = 0.0;
  if (early_count_ >= threshold_) jump = 0.5;
  if (late_count_ >= threshold_) jump = -0.5;
  if (jump != 0.0) {
    early_count_ = late_count_ = 0;
    ++jumps_;
  }
  return jump;
}

}  // namespace deepnav
