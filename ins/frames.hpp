#pragma once
// Local-level (NED) frame geometry on the WGS-84 ellipsoid: the NED <-> ECEF rotation,
// vectors and offsets between the two frames, Earth and transport rates, and the
// elevation/azimuth of a line of sight.
#include <Eigen/Core>

#include "ins/wgs84.hpp"

namespace deepnav {

/// Rotation NED -> ECEF at a geodetic latitude/longitude; its columns are the north,
/// east and down unit vectors expressed in ECEF.
Eigen::Matrix3d C_n_e(double lat_rad, double lon_rad);
/// Rotation ECEF -> NED (transpose of C_n_e).
Eigen::Matrix3d C_e_n(double lat_rad, double lon_rad);

Eigen::Vector3d ecef_to_ned_vector(const wgs84::Llh& at, const Eigen::Vector3d& x_ecef);
Eigen::Vector3d ned_to_ecef_vector(const wgs84::Llh& at, const Eigen::Vector3d& x_ned);

/// Offset of `target` from `reference` (both ECEF), in the NED frame at `reference` (m).
Eigen::Vector3d ned_offset_m(const Eigen::Vector3d& r_reference_ecef_m, const Eigen::Vector3d& r_target_ecef_m);

/// Earth rotation rate w_ie resolved in NED at a latitude.
Eigen::Vector3d earth_rate_ned_radps(double lat_rad);

/// Transport rate w_en_n: rotation rate of the local NED frame relative to the Earth
/// caused by moving over the curved ellipsoid with velocity v_ned.
Eigen::Vector3d transport_rate_ned_radps(const wgs84::Llh& at, const Eigen::Vector3d& v_ned_mps);

/// d(w_en_n)/dt given the NED velocity and its derivative a_ned (the derivative of the
/// NED components, as in TrajectoryState::a_ned_mps2). Exact for the ellipsoid.
Eigen::Vector3d transport_rate_derivative_ned_radps2(const wgs84::Llh& at, const Eigen::Vector3d& v_ned_mps,
                                                     const Eigen::Vector3d& a_ned_mps2);

/// Direction of a line of sight from a receiver, relative to the geodetic local level.
struct LookAngles {
  double elevation_rad = 0.0;  ///< above the local horizontal plane, in [-pi/2, pi/2]
  double azimuth_rad = 0.0;    ///< clockwise from north, in [0, 2*pi)
};
/// Throws std::invalid_argument when the two points coincide.
LookAngles look_angles(const Eigen::Vector3d& r_receiver_ecef_m, const Eigen::Vector3d& r_target_ecef_m);
/// Same, with the receiver's geodetic position already known (saves the ECEF -> LLH step).
LookAngles look_angles(const wgs84::Llh& receiver, const Eigen::Vector3d& r_receiver_ecef_m,
                       const Eigen::Vector3d& r_target_ecef_m);

}  // namespace deepnav
