#include "aiding/imu_feed.hpp"

#include <fmt/format.h>

#include <limits>

namespace deepnav::aiding {

ImuFeed::ImuFeed(const ImuLog& log)
    : log_(log), margin_s_(1.5 * log.nominal_interval_s), last_t_s_(-std::numeric_limits<double>::infinity()) {}

void ImuFeed::advance(double t_s, const std::function<void(const ImuSample&)>& take,
                      const std::function<void(const ImuGap&)>& on_gap, const std::function<void()>& on_end) {
  if (in_gap_ && t_s >= gap_end_t_s_) in_gap_ = false;
  const std::vector<ImuSample>& samples = log_.samples;
  while (next_sample_ < samples.size() && samples[next_sample_].t_s <= t_s + 1e-9) {
    const ImuSample& s = samples[next_sample_];
    // The first sample after a gap not yet reached: the gap lay between two calls.
    if (next_gap_ < log_.gaps.size() && s.t_s >= log_.gaps[next_gap_].t_after_s) on_gap(log_.gaps[next_gap_++]);
    take(s);
    last_t_s_ = s.t_s;
    ++next_sample_;
  }
  if (next_gap_ < log_.gaps.size() && t_s > log_.gaps[next_gap_].t_before_s + margin_s_) {
    const ImuGap& g = log_.gaps[next_gap_++];
    in_gap_ = true;
    gap_end_t_s_ = g.t_after_s;
    on_gap(g);
  }
  if (!ended_ && next_sample_ == samples.size() && !samples.empty() && t_s > samples.back().t_s + margin_s_) {
    ended_ = true;
    on_end();
  }
}

std::string ImuFeed::describe(const ImuGap& gap, double origin_s) const {
  return fmt::format("IMU data missing from t = {:.3f} s to {:.3f} s ({}line {})", gap.t_before_s - origin_s,
                     gap.t_after_s - origin_s, log_.source.empty() ? "IMU file " : log_.source + " ", gap.line);
}

}  // namespace deepnav::aiding
