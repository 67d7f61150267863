#pragma once
// Geometry of one satellite seen from one receiver: signal transmission time from
// the light-time equation, Earth rotation during flight (Sagnac), range, range rate
// and the unit line-of-sight vector. Used by the synthesizer to place the signal and
// by the receiver and the aiding filter to predict it.
#include <Eigen/Core>

#include "ins/gps_time.hpp"
#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"

namespace deepnav {

struct LineOfSight {
  GpsTime transmit_time{};      ///< GPS time the received signal left the satellite (geometric)
  double flight_time_s = 0.0;   ///< geometric range / c
  double range_m = 0.0;         ///< |r_sat(t_tx) rotated to reception frame - r_rx|
  double range_rate_mps = 0.0;  ///< d(range)/dt at reception
  Eigen::Vector3d r_sat_ecef_m = Eigen::Vector3d::Zero();    ///< satellite at t_tx, in the ECEF frame at reception
  Eigen::Vector3d v_sat_ecef_mps = Eigen::Vector3d::Zero();  ///< its velocity, same frame (inertial-consistent)
  Eigen::Vector3d unit_rx_to_sat = Eigen::Vector3d::Zero();
  SatelliteState satellite{};  ///< orbit/clock state at the transmission time
};

/// Solves the light-time equation for a signal received at GPS time t_rx by a receiver
/// at r_rx (ECEF) moving with v_rx (ECEF). Converges to well below a millimetre.
LineOfSight line_of_sight(const Ephemeris& eph, const GpsTime& t_rx, const Eigen::Vector3d& r_rx_ecef_m,
                          const Eigen::Vector3d& v_rx_ecef_mps);
/// The same for a Galileo satellite, whose broadcast model runs on GST: gst_minus_gpst_s (the
/// GGTO) turns the GPS times into GST. transmit_time stays a GPS time; the satellite's clock
/// in `satellite` is on GST.
LineOfSight line_of_sight(const galileo::GalileoEphemeris& eph, double gst_minus_gpst_s, const GpsTime& t_rx,
                          const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& v_rx_ecef_mps);

}  // namespace deepnav
