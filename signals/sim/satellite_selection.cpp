#include "signals/sim/satellite_selection.hpp"

#include <algorithm>
#include <cmath>

#include "ins/frames.hpp"
#include "signals/sim/line_of_sight.hpp"

namespace deepnav {

std::vector<SelectedSatellite> select_satellites(const NavData& nav, const Trajectory& trajectory,
                                                 const SelectionRequest& request) {
  // Check points: start, every 60 s, end.
  std::vector<double> checks;
  for (double t = 0.0; t < request.duration_s; t += 60.0) checks.push_back(t);
  checks.push_back(request.duration_s);

  std::vector<SelectedSatellite> chosen;
  for (int prn = 1; prn <= 32; ++prn) {
    const bool listed = std::find(request.prns.begin(), request.prns.end(), prn) != request.prns.end();
    if (!request.prns.empty() && !listed) continue;
    const Ephemeris* eph = nav.select(prn, request.start);
    if (eph == nullptr || !eph->healthy()) continue;
    SelectedSatellite sat{prn, eph, 0.0, 0.0, 10.0};
    for (double t : checks) {
      const TrajectoryState state = trajectory.at(std::min(t, trajectory.duration_s()));
      const LineOfSight los = line_of_sight(*eph, request.start.plus_seconds(t), state.r_ecef_m, state.v_ecef_mps);
      const LookAngles look = look_angles(state.r_ecef_m, los.r_sat_ecef_m);
      if (t == 0.0) {
        sat.elevation_rad = look.elevation_rad;
        sat.azimuth_rad = look.azimuth_rad;
      }
      sat.min_elevation_rad = std::min(sat.min_elevation_rad, look.elevation_rad);
    }
    const bool visible = listed ? sat.elevation_rad > 0.0 : sat.min_elevation_rad >= request.elevation_mask_rad;
    if (visible) chosen.push_back(sat);
  }
  std::sort(chosen.begin(), chosen.end(),
            [](const SelectedSatellite& a, const SelectedSatellite& b) { return a.elevation_rad > b.elevation_rad; });
  if (static_cast<int>(chosen.size()) > request.max_satellites)
    chosen.resize(static_cast<std::size_t>(request.max_satellites));
  return chosen;
}

}  // namespace deepnav
