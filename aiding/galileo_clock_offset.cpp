#include "aiding/galileo_clock_offset.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav::aiding {

void GalileoClockOffset::add(double t_s, const PvtSolution& fix) {
  if (!fix.valid || !fix.system_offset_m || !std::isfinite(*fix.system_offset_m)) return;
  if (n_ == 0) first_t_s_ = t_s;
  last_t_s_ = t_s;
  ++n_;
  const double d = *fix.system_offset_m - mean_m_;
  mean_m_ += d / n_;
  m2_ += d * (*fix.system_offset_m - mean_m_);
}

std::optional<double> GalileoClockOffset::offset_m() const {
  if (n_ < cfg_.min_fixes) return std::nullopt;
  return mean_m_;
}

double GalileoClockOffset::sigma_m() const {
  if (n_ < 2) return 1e3;  // no scatter yet: unknown
  const double scatter_m = std::sqrt(m2_ / (n_ - 1));
  const double independent = std::max(1.0, (last_t_s_ - first_t_s_) / cfg_.correlation_s);
  return std::max(cfg_.floor_m, scatter_m / std::sqrt(std::min<double>(independent, n_)));
}

}  // namespace deepnav::aiding
