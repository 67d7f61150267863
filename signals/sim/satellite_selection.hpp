#pragma once
// Which satellites a synthesized receiver sees: healthy ones with an ephemeris valid
// at the start, above the elevation mask for the whole run (checked every minute and
// at both ends), strongest (highest) first.
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/trajectory.hpp"
#include "signals/ephemeris.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

struct SelectionRequest {
  GpsTime start{};
  double duration_s = 0.0;
  double elevation_mask_rad = 0.0;
  std::vector<int> prns;  ///< when not empty, only these PRNs are candidates
  int max_satellites = 12;
};

struct SelectedSatellite {
  int prn = 0;
  const Ephemeris* ephemeris = nullptr;  ///< points into the NavData passed in
  double elevation_rad = 0.0;            ///< at the start
  double azimuth_rad = 0.0;
  double min_elevation_rad = 0.0;  ///< lowest over the run's check points
};

/// The satellites to synthesize. Explicitly listed PRNs are kept even below the mask
/// (they must still be above the horizon at the start); the others must clear the mask.
std::vector<SelectedSatellite> select_satellites(const NavData& nav, const Trajectory& trajectory,
                                                 const SelectionRequest& request);

}  // namespace deepnav
