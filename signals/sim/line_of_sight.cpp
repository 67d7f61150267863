#include "signals/sim/line_of_sight.hpp"

#include <cmath>

#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

/// The light-time solution for any broadcast model: state_at(t) is the satellite's state at
/// GPS time t.
template <typename StateAt>
LineOfSight solve_line_of_sight(const StateAt& state_at, const GpsTime& t_rx, const Eigen::Vector3d& r_rx,
                                const Eigen::Vector3d& v_rx) {
  LineOfSight los;
  double tau = 0.075;  // typical flight time; the iteration converges from anywhere near it
  for (int iter = 0; iter < 10; ++iter) {
    los.satellite = state_at(t_rx.plus_seconds(-tau));
    los.r_sat_ecef_m = earth_rotation_corrected(los.satellite.r_ecef_m, tau);
    const double new_tau = (los.r_sat_ecef_m - r_rx).norm() / gps::kSpeedOfLight_mps;
    const bool converged = std::abs(new_tau - tau) < 1e-13;
    tau = new_tau;
    if (converged) break;
  }
  los.satellite = state_at(t_rx.plus_seconds(-tau));
  los.r_sat_ecef_m = earth_rotation_corrected(los.satellite.r_ecef_m, tau);
  // Satellite velocity in the reception-time frame (same rotation as the position).
  los.v_sat_ecef_mps = earth_rotation_corrected(los.satellite.v_ecef_mps, tau);
  los.flight_time_s = tau;
  los.transmit_time = t_rx.plus_seconds(-tau);
  const Eigen::Vector3d d = los.r_sat_ecef_m - r_rx;
  los.range_m = d.norm();
  los.unit_rx_to_sat = d / los.range_m;
  // d(range)/dt_rx with tau = range/c: the rotated satellite position changes through
  // t_tx = t_rx - tau (factor 1 - tau_dot) and through the Sagnac angle omega_e * tau
  // (factor tau_dot). Solving range_rate = u.(d r_sat/dt - v_rx) for range_rate gives
  // range_rate (1 + u.v_sat/c + omega_e u.(z x r_sat)/c) = u.v_sat - u.v_rx.
  const double c = gps::kSpeedOfLight_mps;
  const Eigen::Vector3d z_cross_r(-los.r_sat_ecef_m.y(), los.r_sat_ecef_m.x(), 0.0);
  const double u_dot_vs = los.unit_rx_to_sat.dot(los.v_sat_ecef_mps);
  const double sagnac = gps::kEarthRate_radps * los.unit_rx_to_sat.dot(z_cross_r) / c;
  los.range_rate_mps = (u_dot_vs - los.unit_rx_to_sat.dot(v_rx)) / (1.0 + u_dot_vs / c + sagnac);
  return los;
}

}  // namespace

LineOfSight line_of_sight(const Ephemeris& eph, const GpsTime& t_rx, const Eigen::Vector3d& r_rx,
                          const Eigen::Vector3d& v_rx) {
  return solve_line_of_sight([&eph](const GpsTime& t) { return satellite_state(eph, t); }, t_rx, r_rx, v_rx);
}

LineOfSight line_of_sight(const galileo::GalileoEphemeris& eph, double gst_minus_gpst_s, const GpsTime& t_rx,
                          const Eigen::Vector3d& r_rx, const Eigen::Vector3d& v_rx) {
  return solve_line_of_sight(
      [&](const GpsTime& t) { return galileo::satellite_state(eph, galileo::gst_from_gps_time(t, gst_minus_gpst_s)); },
      t_rx, r_rx, v_rx);
}

}  // namespace deepnav
