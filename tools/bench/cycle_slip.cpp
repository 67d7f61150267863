#include "tools/bench/cycle_slip.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace deepnav::bench {

double interpolate(const std::vector<std::pair<double, double>>& v, double t) {
  const auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(t, -1e300));
  if (it == v.begin()) return v.front().second;
  if (it == v.end()) return v.back().second;
  const auto& [t1, y1] = *it;
  const auto& [t0, y0] = *std::prev(it);
  return y0 + (y1 - y0) * (t - t0) / (t1 - t0);
}

double first_cycle_slip_s(const std::vector<std::pair<double, double>>& nco,
                          const std::vector<std::pair<double, double>>& truth) {
  if (nco.size() < 40 || truth.size() < 2) return nco.empty() ? 0.0 : nco.back().first;
  std::vector<double> plus(nco.size()), minus(nco.size());
  for (std::size_t k = 0; k < nco.size(); ++k) {
    const double p = interpolate(truth, nco[k].first);
    plus[k] = nco[k].second + p;
    minus[k] = nco[k].second - p;
  }
  const auto spread = [](const std::vector<double>& d) { return std::abs(d[20] - d[0]) + std::abs(d[39] - d[20]); };
  const std::vector<double>& d = spread(plus) < spread(minus) ? plus : minus;
  std::size_t back = 0;
  for (std::size_t k = 1; k < d.size(); ++k) {
    while (nco[k].first - nco[back].first > 0.2) ++back;
    if (std::abs(d[k] - d[back]) > 0.35) return nco[k].first;
  }
  return nco.back().first;
}

}  // namespace deepnav::bench
