#include "receiver/pvt/surface_grid.hpp"

#include <gtest/gtest.h>

#include <random>

#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double nearest_m(const std::vector<Eigen::Vector3d>& grid, const Eigen::Vector3d& r) {
  double best = INFINITY;
  for (const auto& g : grid) best = std::min(best, (g - r).norm());
  return best;
}

TEST(SurfaceGrid, CoversEveryPlaceThatSeesTheSatellitesAndNoOther) {
  // Three satellites at GPS altitude above Europe.
  const std::vector<Eigen::Vector3d> sats = {wgs84::llh_to_ecef({50 * kDeg, 10 * kDeg, 20200e3}),
                                             wgs84::llh_to_ecef({30 * kDeg, -20 * kDeg, 20200e3}),
                                             wgs84::llh_to_ecef({60 * kDeg, 40 * kDeg, 20200e3})};
  const double spacing = 200e3;
  const auto grid = visible_surface_grid(sats, spacing, 0.0);
  ASSERT_GT(grid.size(), 100u);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> lat(20.0, 80.0), lon(-60.0, 80.0);
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    const wgs84::Llh llh{lat(rng) * kDeg, lon(rng) * kDeg, 0.0};
    const Eigen::Vector3d r = wgs84::llh_to_ecef(llh);
    const Eigen::Vector3d up(std::cos(llh.lat_rad) * std::cos(llh.lon_rad),
                             std::cos(llh.lat_rad) * std::sin(llh.lon_rad), std::sin(llh.lat_rad));
    double min_sin = 1.0;
    for (const auto& s : sats) min_sin = std::min(min_sin, up.dot((s - r).normalized()));
    // Well inside the visible region every place has a grid point within spacing/sqrt(2).
    if (min_sin > std::sin(5 * kDeg)) {
      ++inside;
      EXPECT_LT(nearest_m(grid, r), spacing / std::sqrt(2.0) * 1.05);
    }
  }
  EXPECT_GT(inside, 200);
  for (const auto& g : grid) {
    for (const auto& s : sats) EXPECT_GE(g.normalized().dot((s - g).normalized()), -0.01);
  }
}

TEST(SurfaceGrid, AroundAPointStaysWithinTheRadius) {
  const Eigen::Vector3d centre = wgs84::llh_to_ecef({64 * kDeg, -22 * kDeg, 500.0});
  const auto grid = surface_grid_around(centre, 350e3, 100e3);
  EXPECT_EQ(grid.size(), 37u);  // the points of a 100 km square lattice within 3.5 spacings of the centre
  EXPECT_NEAR(wgs84::ecef_to_llh(grid.front()).height_m, 0.0, 1e-6);
  EXPECT_LT((grid.front() - centre).norm(), 501.0);
  for (const auto& g : grid) EXPECT_LT((g - centre).norm(), 352e3);
  EXPECT_THROW(surface_grid_around(centre, 100e3, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
