#pragma once
// Per-satellite fault detection and exclusion for the range updates (tight and
// ultra-tight). The filter's row gate turns away single wild rows against the prior, but a
// satellite with a persistent fault (a step in its clock, an NLOS path, a multipath bias
// of several sigma) either keeps being turned away, row after row, until the innovation
// monitor restarts the whole filter, or, when its bias stays under the gate, pulls the
// solution by a fraction of it for as long as it lasts. This monitor watches each
// satellite's normalised pseudorange innovations over its last rows and excludes the
// satellite, alone, when
//   - more than `max_rejected_fraction` of its rows failed the gate, or
//   - the mean of its normalised innovations is beyond `max_mean_sigma` (a bias: a
//     consistent filter's innovations have zero mean and unit variance),
// and keeps it out for `hold_s`, re-admitting it only once its innovations (still
// computed, not used) pass the same tests again. Excluded rows do not count against the
// filter as a whole.
#include <deque>
#include <map>
#include <vector>

#include "signals/satellite_id.hpp"

namespace deepnav::aiding {

struct SatelliteFaultConfig {
  double window_s = 5.0;  ///< the tests look at the rows of the last window_s,
  int max_rows = 20;      ///< at most this many (ultra-tight's 100 Hz: 0.2 s)
  int min_rows = 3;       ///< fewer rows than this say nothing
  double max_rejected_fraction = 0.5;
  double max_mean_sigma = 3.0;
  double hold_s = 5.0;  ///< an exclusion lasts at least this long
};

/// One satellite's pseudorange row at one update: its innovation over its predicted sigma
/// (against the prior), and whether the row gate turned it away.
struct SatelliteInnovation {
  SatelliteId satellite;
  double normalized = 0.0;
  bool rejected = false;
};

class SatelliteFaultMonitor {
 public:
  explicit SatelliteFaultMonitor(SatelliteFaultConfig config = {}) : cfg_(config) {}

  /// The rows of one update at t_s (non-decreasing), used or test-only.
  void add(double t_s, const std::vector<SatelliteInnovation>& rows);
  /// Whether the satellite's measurements are kept out of the filter at t_s.
  bool excluded(const SatelliteId& satellite) const;
  /// Satellites excluded now.
  std::vector<SatelliteId> excluded_satellites() const;
  /// How many times a satellite was excluded (each start of an exclusion counts once).
  int exclusions() const { return exclusions_; }
  void clear();

 private:
  struct Row {
    double t_s;
    double normalized;
    bool rejected;
  };
  struct Track {
    std::deque<Row> rows;
    bool excluded = false;
    double excluded_since_s = 0.0;
  };
  /// Whether the rows in the window say the satellite is faulty (false with too few rows).
  bool faulty(const Track& track) const;
  SatelliteFaultConfig cfg_;
  std::map<SatelliteId, Track> tracks_;
  int exclusions_ = 0;
};

}  // namespace deepnav::aiding
