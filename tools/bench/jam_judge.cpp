#include "tools/bench/jam_judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace deepnav::bench {

JamVerdict judge_jam_point(const JamChannels& channels, const JamSolutionFigures& solution,
                           const FailureCriteria& criteria) {
  JamVerdict v;
  double tracked_sum = 0.0, tracked_min = 1.0, signal_sum = 0.0, cn0_sum = 0.0;
  int n = 0, n_cn0 = 0;
  for (const auto& [prn, ch] : channels) {
    tracked_sum += ch.tracked_fraction;
    tracked_min = std::min(tracked_min, ch.tracked_fraction);
    signal_sum += ch.signal_fraction;
    ++n;
    if (ch.cn0_dbhz) {
      cn0_sum += *ch.cn0_dbhz;
      ++n_cn0;
    }
  }
  v.tracked_fraction_mean = n ? tracked_sum / n : 0.0;
  v.tracked_fraction_min = n ? tracked_min : 0.0;
  v.signal_fraction_mean = n ? signal_sum / n : 0.0;
  if (n_cn0) v.cn0_mean_dbhz = cn0_sum / n_cn0;

  std::vector<std::string> reasons;
  if (solution.fix_availability < criteria.min_fix_availability) reasons.push_back("GNSS fixes missing");
  const auto over = [&](const std::optional<double>& error_m) { return error_m && *error_m > criteria.max_error_m; };
  if (over(solution.horizontal_max_m) || over(solution.vertical_max_m))
    reasons.push_back(fmt::format("error over {:g} m", criteria.max_error_m));
  if (v.tracked_fraction_mean < criteria.min_tracked_fraction) reasons.push_back("tracking lost");
  for (const auto& r : reasons) v.failure += (v.failure.empty() ? "" : "; ") + r;
  v.failed = !reasons.empty();
  return v;
}

}  // namespace deepnav::bench
