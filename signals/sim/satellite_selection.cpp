#include "signals/sim/satellite_selection.hpp"

#include <algorithm>
#include <cmath>

#include "ins/frames.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "signals/sim/line_of_sight.hpp"

namespace deepnav {
namespace {

/// Check points: start, every 60 s, end.
std::vector<double> check_points(double duration_s) {
  std::vector<double> checks;
  for (double t = 0.0; t < duration_s; t += 60.0) checks.push_back(t);
  checks.push_back(duration_s);
  return checks;
}

void sort_and_cap(std::vector<SelectedSatellite>& chosen, int max_satellites) {
  std::sort(chosen.begin(), chosen.end(),
            [](const SelectedSatellite& a, const SelectedSatellite& b) { return a.elevation_rad > b.elevation_rad; });
  if (static_cast<int>(chosen.size()) > max_satellites) chosen.resize(static_cast<std::size_t>(max_satellites));
}

bool wants(const SelectionRequest& request, GnssSystem system) {
  return std::find(request.systems.begin(), request.systems.end(), system) != request.systems.end();
}

/// Sets the satellite's look angles at the start and its lowest elevation over the check
/// points; `r_sat_ecef_at(t, state)` is its position t seconds after the start, seen from the
/// trajectory's state then. Whether it is chosen: a listed satellite when above the horizon at
/// the start, any other when above the mask throughout.
template <class SatellitePosition>
bool sweep_elevation(SelectedSatellite& sat, const Trajectory& trajectory, const SelectionRequest& request, bool listed,
                     const SatellitePosition& r_sat_ecef_at) {
  sat.min_elevation_rad = 10.0;
  for (double t : check_points(request.duration_s)) {
    const TrajectoryState state = trajectory.at(std::min(t, trajectory.duration_s()));
    const LookAngles look = look_angles(state.r_ecef_m, r_sat_ecef_at(t, state));
    if (t == 0.0) {
      sat.elevation_rad = look.elevation_rad;
      sat.azimuth_rad = look.azimuth_rad;
    }
    sat.min_elevation_rad = std::min(sat.min_elevation_rad, look.elevation_rad);
  }
  return listed ? sat.elevation_rad > 0.0 : sat.min_elevation_rad >= request.elevation_mask_rad;
}

std::vector<SelectedSatellite> select_galileo(const NavData& nav, const Trajectory& trajectory,
                                              const SelectionRequest& request) {
  const galileo::GstTime start = galileo::gst_from_gps_time(request.start, request.gst_minus_gpst_s);
  std::vector<SelectedSatellite> chosen;
  for (int svid = 1; svid <= galileo::kMaxPrn; ++svid) {
    const bool listed =
        std::find(request.galileo_prns.begin(), request.galileo_prns.end(), svid) != request.galileo_prns.end();
    if (!request.galileo_prns.empty() && !listed) continue;
    const galileo::GalileoEphemeris* eph = select_galileo_ephemeris(nav, svid, start);
    if (eph == nullptr) continue;
    SelectedSatellite sat;
    sat.prn = svid;
    sat.id = SatelliteId{GnssSystem::galileo, svid};
    sat.galileo_ephemeris = eph;
    const auto r_sat_ecef_at = [&](double t, const TrajectoryState& state) {
      return line_of_sight(*eph, request.gst_minus_gpst_s, request.start.plus_seconds(t), state.r_ecef_m,
                           state.v_ecef_mps)
          .r_sat_ecef_m;
    };
    if (sweep_elevation(sat, trajectory, request, listed, r_sat_ecef_at)) chosen.push_back(sat);
  }
  sort_and_cap(chosen, request.max_satellites);
  return chosen;
}

std::vector<SelectedSatellite> select_gps(const NavData& nav, const Trajectory& trajectory,
                                          const SelectionRequest& request) {
  std::vector<SelectedSatellite> chosen;
  for (int prn = 1; prn <= 32; ++prn) {
    const bool listed = std::find(request.prns.begin(), request.prns.end(), prn) != request.prns.end();
    if (!request.prns.empty() && !listed) continue;
    const Ephemeris* eph = nav.select(prn, request.start);
    if (eph == nullptr || !eph->healthy()) continue;
    SelectedSatellite sat;
    sat.prn = prn;
    sat.ephemeris = eph;
    sat.id = SatelliteId{GnssSystem::gps, prn};
    const auto r_sat_ecef_at = [&](double t, const TrajectoryState& state) {
      return line_of_sight(*eph, request.start.plus_seconds(t), state.r_ecef_m, state.v_ecef_mps).r_sat_ecef_m;
    };
    if (sweep_elevation(sat, trajectory, request, listed, r_sat_ecef_at)) chosen.push_back(sat);
  }
  sort_and_cap(chosen, request.max_satellites);
  return chosen;
}

}  // namespace

std::vector<SelectedSatellite> select_satellites(const NavData& nav, const Trajectory& trajectory,
                                                 const SelectionRequest& request) {
  std::vector<SelectedSatellite> chosen;
  if (wants(request, GnssSystem::gps)) chosen = select_gps(nav, trajectory, request);
  if (wants(request, GnssSystem::galileo)) {
    const auto galileo = select_galileo(nav, trajectory, request);
    chosen.insert(chosen.end(), galileo.begin(), galileo.end());
  }
  return chosen;
}

}  // namespace deepnav
