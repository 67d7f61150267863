#include "aiding/satellite_fault_monitor.hpp"

#include <cmath>

namespace deepnav::aiding {

void SatelliteFaultMonitor::add(double t_s, const std::vector<SatelliteInnovation>& rows) {
  for (const SatelliteInnovation& r : rows) {
    if (!std::isfinite(r.normalized)) continue;
    tracks_[r.satellite].rows.push_back({t_s, r.normalized, r.rejected});
  }
  for (auto& [satellite, track] : tracks_) {
    while (!track.rows.empty() &&
           (track.rows.front().t_s <= t_s - cfg_.window_s || static_cast<int>(track.rows.size()) > cfg_.max_rows))
      track.rows.pop_front();
    const bool bad = faulty(track);
    if (!track.excluded && bad) {
      track.excluded = true;
      track.excluded_since_s = t_s;
      ++exclusions_;
    } else if (track.excluded && !bad && t_s - track.excluded_since_s >= cfg_.hold_s &&
               static_cast<int>(track.rows.size()) >= cfg_.min_rows) {
      track.excluded = false;
    }
  }
}

bool SatelliteFaultMonitor::faulty(const Track& track) const {
  const int n = static_cast<int>(track.rows.size());
  if (n < cfg_.min_rows) return false;
  int rejected = 0;
  double sum = 0.0;
  for (const Row& r : track.rows) {
    rejected += r.rejected ? 1 : 0;
    sum += r.normalized;
  }
  return rejected > cfg_.max_rejected_fraction * n || std::abs(sum / n) > cfg_.max_mean_sigma;
}

bool SatelliteFaultMonitor::excluded(const SatelliteId& satellite) const {
  const auto it = tracks_.find(satellite);
  return it != tracks_.end() && it->second.excluded;
}

std::vector<SatelliteId> SatelliteFaultMonitor::excluded_satellites() const {
  std::vector<SatelliteId> out;
  for (const auto& [satellite, track] : tracks_)
    if (track.excluded) out.push_back(satellite);
  return out;
}

void SatelliteFaultMonitor::clear() { tracks_.clear(); }

}  // namespace deepnav::aiding
