#include "tools/bench/coupling_scoring.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav::bench {

RunScore score_run(const nlohmann::json& epochs, const std::string& mode, double score_from_s, double score_at_s) {
  RunScore s;
  double sum_h = 0.0, sum_v = 0.0;
  int n = 0;
  for (const auto& e : epochs) {
    const double t = e[0].get<double>();
    if (t < score_from_s) continue;
    s.scored_s += 1.0;
    if (e[1].get<std::string>() == mode) s.in_mode_s += 1.0;
    if (!e[2].get<bool>()) continue;
    const Eigen::Vector3d err(e[3].get<double>(), e[4].get<double>(), e[5].get<double>());
    sum_h += err.head<2>().squaredNorm();
    sum_v += err(2) * err(2);
    ++n;
    if (std::abs(t - score_at_s) < 1e-6) s.error_at_m = err;
  }
  if (n > 0) {
    s.rms_h_m = std::sqrt(sum_h / n);
    s.rms_3d_m = std::sqrt((sum_h + sum_v) / n);
  }
  return s;
}

double vertical_rms_from(const nlohmann::json& epochs, double from_s) {
  double sum_v = 0.0;
  int n = 0;
  for (const auto& e : epochs) {
    if (e[0].get<double>() < from_s || !e[2].get<bool>()) continue;
    sum_v += e[5].get<double>() * e[5].get<double>();
    ++n;
  }
  return n > 0 ? std::sqrt(sum_v / n) : NAN;
}

std::optional<double> mismatch_found_s(const nlohmann::json& mode_record) {
  std::optional<double> first;
  for (const char* key : {"troposphere_mismatch_s", "ionosphere_mismatch_s"})
    if (mode_record.contains(key) && !mode_record[key].is_null()) {
      const double t = mode_record[key].get<double>();
      first = first ? std::min(*first, t) : t;
    }
  return first;
}

Spread spread(const std::vector<double>& v) {
  Spread s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  double ss = 0.0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std = s.n > 1 ? std::sqrt(ss / (s.n - 1)) : 0.0;
  return s;
}

std::string paired_verdict(const std::vector<double>& better, const std::vector<double>& worse) {
  std::vector<double> d;
  for (std::size_t i = 0; i < std::min(better.size(), worse.size()); ++i) d.push_back(better[i] - worse[i]);
  const Spread s = spread(d);
  if (s.n < 2) return s.n == 1 ? (s.mean <= 0.0 ? "yes(1 run)" : "no(1 run)") : "n/a";
  const double se = s.std / std::sqrt(static_cast<double>(s.n));
  if (s.mean < -2.0 * se) return "yes";
  if (s.mean > 2.0 * se) return "no";
  return "tie";
}

}  // namespace deepnav::bench
