#pragma once
// Candidate receiver positions on the Earth's surface for a fix without a position hint:
// a grid over the region from which every measured satellite is above the horizon (a
// receiver sees all of them, so it is there), or a grid around a first position.
//
// Points lie on the WGS-84 ellipsoid (height 0), spaced about `spacing_m` along the
// meridians and the parallels, so no place is farther than spacing / sqrt(2) from one.
#include <Eigen/Core>
#include <vector>

namespace deepnav {

/// Grid points from which every satellite in `satellites_ecef_m` is at least
/// `min_elevation_rad` above the local horizontal (geodetic).
std::vector<Eigen::Vector3d> visible_surface_grid(const std::vector<Eigen::Vector3d>& satellites_ecef_m,
                                                  double spacing_m, double min_elevation_rad);

/// Grid points within `radius_m` (along the surface, locally flat) of `centre_ecef_m`,
/// the point on the ellipsoid below the centre first.
std::vector<Eigen::Vector3d> surface_grid_around(const Eigen::Vector3d& centre_ecef_m, double radius_m,
                                                 double spacing_m);

}  // namespace deepnav
