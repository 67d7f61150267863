#pragma once
// Which satellites a synthesized receiver sees: healthy ones with an ephemeris valid
// at the start, above the elevation mask for the whole run (checked every minute and
// at both ends), strongest (highest) first: GPS satellites, then Galileo ones (each system
// sorted and capped on its own, so adding Galileo leaves the GPS choice as it was).
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/trajectory.hpp"
#include "signals/ephemeris.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

struct SelectionRequest {
  GpsTime start{};
  double duration_s = 0.0;
  double elevation_mask_rad = 0.0;
  std::vector<int> prns;          ///< when not empty, only these GPS PRNs are candidates
  std::vector<int> galileo_prns;  ///< when not empty, only these Galileo SVIDs are candidates
  int max_satellites = 12;        ///< per system
  std::vector<GnssSystem> systems{GnssSystem::gps};
  double gst_minus_gpst_s = 0.0;  ///< GGTO, for Galileo orbits (on GST)
};

struct SelectedSatellite {
  int prn = 0;
  const Ephemeris* ephemeris = nullptr;  ///< points into the NavData passed in (GPS)
  SatelliteId id{};
  const galileo::GalileoEphemeris* galileo_ephemeris = nullptr;  ///< points into the NavData (Galileo)
  double elevation_rad = 0.0;                                    ///< at the start
  double azimuth_rad = 0.0;
  double min_elevation_rad = 0.0;  ///< lowest over the run's check points
};

/// The satellites to synthesize. Explicitly listed PRNs are kept even below the mask
/// (they must still be above the horizon at the start); the others must clear the mask.
std::vector<SelectedSatellite> select_satellites(const NavData& nav, const Trajectory& trajectory,
                                                 const SelectionRequest& request);

}  // namespace deepnav
