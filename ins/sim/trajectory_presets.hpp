#pragma once
// Analytic vehicle trajectories and the named scenarios of paper 003 [docs/references.md].
//
// Construction: the horizontal path is a chain of segments (straight with constant
// acceleration, or an arc at constant speed and turn rate) plus a constant climb rate,
// laid out in the local-level (NED) tangent plane at the start point and mapped to
// ECEF exactly, so position, velocity and acceleration are analytic and mutually
// consistent. Attitude is defined in that tangent frame (yaw along the course, pitch
// along the flight path, roll = coordinated-turn bank for aircraft, 0 for land
// vehicles, or the wing-rock oscillation) and expressed against the local NED frame
// of the current position. The body rate w.r.t. local NED and its derivative come from
// high-order central differences of that attitude (error well below 1e-9 rad/s).
//
// Presets (paper 003; 200 s runs in the paper):
//   static          no motion (heading from the argument)
//   land-straight   10 km/h straight
//   land-accel      straight from rest at 0.1 m/s^2
//   land-circle     r = 87.27 m at 10 km/h (turn rate ~ pi/100 rad/s)
//   land-s          half circle of land-circle, then half circle the other way, repeated
//   air-circle      r = 4422 m at 500 km/h (turn rate pi/100 rad/s), coordinated bank
//   air-s           half circle of air-circle, then the other way, repeated; the bank
//                   reverses smoothly over 4 s centred on each reversal (the path itself
//                   switches curvature at once; only the roll anticipates and lags)
//   air-spiral      r = 4422 m at turn rate pi/50 rad/s (as the paper states), climbing 0.2 m/s
//   air-wingrock    straight and level at 500 km/h, roll +-20 deg with a 10 s period
//                   (the paper gives no period)
//   air-*-x2        the aircraft set with doubled rates/angles (paper 003 Table 3): turn rates
//                   doubled at the same speed (radius halved); wing-rock amplitude +-40 deg.
#include <memory>
#include <string>
#include <vector>

#include "ins/trajectory.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {

/// One piece of the horizontal path, in the tangent plane.
struct PathSegment {
  double duration_s = 0.0;       ///< infinity for the last, open-ended segment
  double accel_mps2 = 0.0;       ///< along-track acceleration (straight segments only)
  double turn_rate_radps = 0.0;  ///< course rate, positive turning right (clockwise seen from above)
};

/// Description of an analytic trajectory.
struct PathSpec {
  std::string name;
  wgs84::Llh start{};
  double heading_rad = 0.0;           ///< initial course, clockwise from north
  double speed_mps = 0.0;             ///< initial horizontal speed
  double climb_mps = 0.0;             ///< constant rate of climb (up positive)
  std::vector<PathSegment> segments;  ///< repeated cyclically when `repeat`
  bool repeat = false;
  bool bank_in_turns = false;  ///< aircraft: coordinated-turn roll = atan(v * turn rate / g)
  /// Aircraft: time over which the bank follows a change of turn rate (quintic blend centred
  /// on the change, e.g. the S-shape's reversals); 0 makes the bank jump with the turn rate.
  double roll_reversal_s = 4.0;
  double wingrock_amplitude_rad = 0.0;
  double wingrock_period_s = 10.0;
  double duration_s = 0.0;  ///< reported by duration_s() (the path itself is defined beyond it)
};

/// A trajectory built from a PathSpec.
std::unique_ptr<Trajectory> make_path_trajectory(const PathSpec& spec);

/// A named preset (list above). Throws std::invalid_argument listing the valid names.
std::unique_ptr<Trajectory> make_preset_trajectory(const std::string& name, const wgs84::Llh& start, double heading_rad,
                                                   double duration_s);
std::vector<std::string> preset_trajectory_names();

}  // namespace deepnav
