#include "receiver/pvt/surface_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

Eigen::Vector3d geodetic_up(double lat_rad, double lon_rad) {
  return {std::cos(lat_rad) * std::cos(lon_rad), std::cos(lat_rad) * std::sin(lon_rad), std::sin(lat_rad)};
}

bool sees_all(const Eigen::Vector3d& r_ecef_m, const Eigen::Vector3d& up,
              const std::vector<Eigen::Vector3d>& satellites_ecef_m, double min_sin_elevation) {
  return std::all_of(satellites_ecef_m.begin(), satellites_ecef_m.end(), [&](const Eigen::Vector3d& sat) {
    const Eigen::Vector3d d = sat - r_ecef_m;
    return up.dot(d) >= min_sin_elevation * d.norm();
  });
}

void check_spacing(double spacing_m) {
  if (!(spacing_m >= 1e3)) throw std::invalid_argument("surface grid: spacing must be at least 1 km");
}

}  // namespace

std::vector<Eigen::Vector3d> visible_surface_grid(const std::vector<Eigen::Vector3d>& satellites_ecef_m,
                                                  double spacing_m, double min_elevation_rad) {
  check_spacing(spacing_m);
  const double min_sin = std::sin(min_elevation_rad);
  const double step_rad = spacing_m / wgs84::kSemiMajorAxis_m;
  const int rows = static_cast<int>(std::ceil(std::numbers::pi / step_rad));
  std::vector<Eigen::Vector3d> grid;
  for (int i = 0; i <= rows; ++i) {
    const double lat = -std::numbers::pi / 2 + std::numbers::pi * i / rows;
    // As many points on this parallel as fit at the spacing (one at a pole).
    const int columns = std::max(1, static_cast<int>(std::ceil(2.0 * std::numbers::pi * std::cos(lat) / step_rad)));
    for (int j = 0; j < columns; ++j) {
      const double lon = -std::numbers::pi + 2.0 * std::numbers::pi * j / columns;
      const Eigen::Vector3d r = wgs84::llh_to_ecef({lat, lon, 0.0});
      if (sees_all(r, geodetic_up(lat, lon), satellites_ecef_m, min_sin)) grid.push_back(r);
    }
  }
  return grid;
}

std::vector<Eigen::Vector3d> surface_grid_around(const Eigen::Vector3d& centre_ecef_m, double radius_m,
                                                 double spacing_m) {
  check_spacing(spacing_m);
  const wgs84::Llh centre = wgs84::ecef_to_llh(centre_ecef_m);
  const double north_m_per_rad = wgs84::meridian_radius_m(centre.lat_rad);
  const double east_m_per_rad = std::max(wgs84::transverse_radius_m(centre.lat_rad) * std::cos(centre.lat_rad), 1.0);
  const int steps = static_cast<int>(std::floor(radius_m / spacing_m));
  std::vector<Eigen::Vector3d> grid{wgs84::llh_to_ecef({centre.lat_rad, centre.lon_rad, 0.0})};
  for (int i = -steps; i <= steps; ++i) {
    for (int j = -steps; j <= steps; ++j) {
      const double north_m = i * spacing_m, east_m = j * spacing_m;
      if ((i == 0 && j == 0) || std::hypot(north_m, east_m) > radius_m) continue;
      const double lat =
          std::clamp(centre.lat_rad + north_m / north_m_per_rad, -std::numbers::pi / 2, std::numbers::pi / 2);
      grid.push_back(wgs84::llh_to_ecef({lat, centre.lon_rad + east_m / east_m_per_rad, 0.0}));
    }
  }
  return grid;
}

}  // namespace deepnav
