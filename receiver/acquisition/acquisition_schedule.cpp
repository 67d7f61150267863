#include "receiver/acquisition/acquisition_schedule.hpp"

#include <algorithm>
#include <cmath>

#include "receiver/acquisition/signal_diagnostics.hpp"

namespace deepnav {
namespace {

std::size_t samples_of_one_search(const AcquisitionConfig& c) {
  const std::int64_t per_ms = std::llround(c.sample_rate_hz * 1e-3);
  return static_cast<std::size_t>(per_ms * c.coherent_ms * c.noncoherent);
}

}  // namespace

AcquisitionSchedule::AcquisitionSchedule(AcquisitionConfig config, double reacquire_interval_s)
    : cfg_(std::move(config)),
      interval_s_(reacquire_interval_s),
      window_samples_(samples_of_one_search(cfg_)),
      window_(window_samples_) {}

bool AcquisitionSchedule::searchable(int prn) const {
  return cfg_.prns.empty() || std::count(cfg_.prns.begin(), cfg_.prns.end(), prn);
}

void AcquisitionSchedule::keep(const SampleBlock& block, bool channel_free) {
  if (channel_free) window_.append(block.samples.data(), block.samples.size(), block.first_sample_index);
  else window_.clear();
}

bool AcquisitionSchedule::reacquisition_due(double t_s, bool channel_free) {
  if (t_s - last_search_s_ < interval_s_ || !channel_free || !window_.full()) return false;
  last_search_s_ = t_s;
  return true;
}

std::vector<AcquisitionResult> AcquisitionSchedule::search(const std::vector<Sample>& samples,
                                                           const std::vector<int>& prns) {
  if (!engine_) engine_ = std::make_unique<Acquisition>(cfg_);
  // Fewer than one coherent block per non-coherent sum: nothing to search with.
  if (static_cast<std::int64_t>(samples.size()) < engine_->samples_needed() / std::max(1, cfg_.noncoherent)) return {};
  std::vector<AcquisitionResult> results = engine_->search(samples, prns);
  if (const auto best = strongest_correlation(results);
      best && (!strongest_ || threshold_ratio(*best) > threshold_ratio(*strongest_)))
    strongest_ = best;
  std::sort(results.begin(), results.end(), [](const auto& a, const auto& b) { return a.cn0_dbhz > b.cn0_dbhz; });
  std::erase_if(results, [](const AcquisitionResult& r) { return !r.detected; });
  return results;
}

}  // namespace deepnav
