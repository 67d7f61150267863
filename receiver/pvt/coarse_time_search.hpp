#pragma once
// A coarse-time fix without a position hint: candidate positions whose predicted ranges
// give the whole milliseconds, each set fitted once and tested (no exclusions: across
// hundreds of sets, dropping a satellite would let wrong ones pass).
//
// Candidates. With 5 or more Dopplers, the Doppler position (doppler_position.hpp: tens
// of km) and a grid around it that covers 3 sigma of it; a fix must lie in that region.
// Without them, or when the Dopplers fit no static receiver (a moving one), a grid over
// every place from which all the satellites are above the horizon (surface_grid.hpp);
// that needs `min_grid_satellites` so that no wrong set passes by chance. Grid spacing
// 100 km: every place lies within 71 km of a candidate, inside the 150 km the whole
// milliseconds tolerate.
//
// Candidates only choose whole milliseconds, so their ranges are predicted cheaply:
// satellite positions and clocks at the hinted time less a typical 75 ms flight (their
// error, tens of metres, is nothing next to the 150 km). Sets seen before are skipped.
//
// A false detection (a long snapshot's non-coherent sum over many PRNs) can name a
// satellite that no place sees together with the others: the visible region is then
// empty. When leaving out exactly one satellite gives a region again, that satellite is
// set aside (unseen_prns) and the region of the rest is searched.
#include <optional>
#include <string>
#include <vector>

#include "receiver/pvt/coarse_time_config.hpp"
#include "receiver/pvt/coarse_time_fit.hpp"
#include "receiver/pvt/coarse_time_integrity.hpp"
#include "receiver/pvt/doppler_position.hpp"

namespace deepnav {

struct CoarseTimeSearch {
  std::vector<CheckedCoarseTimeFit> fixes;  ///< passing and plausible, one per distinct place
  /// Passing, at a plausible place, but with a time correction beyond the tolerance: what
  /// says how far off the time hint is when no fix is found.
  std::vector<CheckedCoarseTimeFit> beyond_time_tolerance;
  bool from_doppler = false;               ///< the fixes come from around the Doppler position
  bool searched_visible_region = false;    ///< the global grid was searched
  std::optional<DopplerPosition> doppler;  ///< when Dopplers were given
  int candidates = 0;                      ///< whole-millisecond sets tried
  bool too_few_satellites = false;         ///< for the global grid, and no Doppler position
  /// Satellites left out because no place sees them with the others: a detection of a
  /// signal that is not there (its whole-millisecond sets would all fail anyway).
  std::vector<int> unseen_prns;
  std::string reason;  ///< when no candidate could be made
};

CoarseTimeSearch search_without_position(const std::vector<CoarseTimeSatellite>& satellites,
                                         const std::vector<DopplerSatellite>& dopplers,
                                         const CoarseTimeContext& context, const CoarseTimeConfig& config);

}  // namespace deepnav
