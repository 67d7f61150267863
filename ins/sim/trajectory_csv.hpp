#pragma once
// A user trajectory from a CSV file, interpolated smoothly (C2).
//
// The first line names the columns, which must be, in this order, either
//   t_s,lat_deg,lon_deg,height_m            (geodetic)   or
//   t_s,x_ecef_m,y_ecef_m,z_ecef_m          (ECEF),
// each optionally followed by roll_deg,pitch_deg,yaw_deg (attitude of the body
// frame, x forward / y right / z down, against local NED). At least 4 rows, time
// strictly increasing; blank lines and lines starting with '#' are skipped.
// Position: natural cubic spline per ECEF axis (velocity and acceleration are its
// derivatives). Attitude: cubic splines of the Euler angles (yaw unwrapped); without
// attitude columns, yaw and pitch follow the velocity (roll 0; yaw held below
// 0.1 m/s). Body rates come from the attitude's time derivatives. Times outside the
// file's span throw std::out_of_range. The time column is trajectory time: seconds
// from the scenario start, so the file must cover [0, duration].
#include <iosfwd>
#include <memory>
#include <string>

#include "ins/trajectory.hpp"

namespace deepnav {

/// Throws std::runtime_error naming the file and line for malformed input.
std::unique_ptr<Trajectory> load_csv_trajectory(const std::string& path);
/// Same from a stream; `name` stands for the file in messages.
std::unique_ptr<Trajectory> load_csv_trajectory(std::istream& in, const std::string& name);

}  // namespace deepnav
