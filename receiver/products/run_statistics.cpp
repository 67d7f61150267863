#include "receiver/products/run_statistics.hpp"

#include <algorithm>
#include <cmath>

#include "ins/frames.hpp"

namespace deepnav {

namespace {
/// Over the sorted values, so the figure does not depend on the order they came in.
double rms_of_sorted(const std::vector<double>& s) {
  double sum2 = 0.0;
  for (double x : s) sum2 += x * x;
  return s.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(s.size()));
}
}  // namespace

double ValueStatistics::rms() const {
  std::vector<double> s = values;
  std::sort(s.begin(), s.end());
  return rms_of_sorted(s);
}

nlohmann::json ValueStatistics::json() const {
  if (values.empty()) return nullptr;
  std::vector<double> s = values;
  std::sort(s.begin(), s.end());
  return {{"rms", rms_of_sorted(s)},
          {"p95", s[static_cast<std::size_t>(0.95 * static_cast<double>(s.size() - 1))]},
          {"max", s.back()},
          {"count", s.size()}};
}

void RunStatistics::on_epoch(const NavigationEpoch& e) {
  ++epochs_;
  const PvtSolution& p = e.solution;
  if (!p.valid) return;
  ++fixes_;
  if (!first_fix_s_) first_fix_s_ = e.receiver.t_s;
  pdop_.values.push_back(p.dops.pdop);
  satellites_.values.push_back(static_cast<double>(p.used_satellites.size()));
  if (!truth_) return;
  if (const auto t = truth_->at(e.receiver.t_s)) {
    const Eigen::Vector3d d = C_e_n(p.llh.lat_rad, p.llh.lon_rad) * (p.r_ecef_m - t->r_ecef_m);
    horizontal_.values.push_back(d.head<2>().norm());
    vertical_.values.push_back(std::abs(d.z()));
    velocity_.values.push_back((p.v_ecef_mps - t->v_ecef_mps).norm());
  }
}

}  // namespace deepnav
