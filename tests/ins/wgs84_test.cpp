#include "ins/wgs84.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Wgs84, KnownPointsOnTheAxes) {
  const Eigen::Vector3d equator = wgs84::llh_to_ecef({0.0, 0.0, 0.0});
  EXPECT_NEAR(equator.x(), 6378137.0, 1e-6);
  EXPECT_NEAR(equator.y(), 0.0, 1e-6);
  EXPECT_NEAR(equator.z(), 0.0, 1e-6);

  const Eigen::Vector3d east = wgs84::llh_to_ecef({0.0, 90.0 * kDeg, 100.0});
  EXPECT_NEAR(east.x(), 0.0, 1e-6);
  EXPECT_NEAR(east.y(), 6378237.0, 1e-6);

  const Eigen::Vector3d north_pole = wgs84::llh_to_ecef({90.0 * kDeg, 0.0, 0.0});
  EXPECT_NEAR(north_pole.z(), 6356752.314245, 1e-6);  // semi-minor axis b
  const Eigen::Vector3d south_pole = wgs84::llh_to_ecef({-90.0 * kDeg, 0.0, 1000.0});
  EXPECT_NEAR(south_pole.z(), -6357752.314245, 1e-6);
  EXPECT_NEAR(std::hypot(south_pole.x(), south_pole.y()), 0.0, 1e-6);
}

TEST(Wgs84, InverseOfKnownPoints) {
  const wgs84::Llh pole = wgs84::ecef_to_llh({0.0, 0.0, 6356752.314245 + 500.0});
  EXPECT_NEAR(pole.lat_rad, 90.0 * kDeg, 1e-12);
  EXPECT_NEAR(pole.height_m, 500.0, 1e-6);
  const wgs84::Llh eq = wgs84::ecef_to_llh({-6378137.0 - 20.0, 0.0, 0.0});
  EXPECT_NEAR(eq.lat_rad, 0.0, 1e-12);
  EXPECT_NEAR(std::abs(eq.lon_rad), std::numbers::pi, 1e-12);
  EXPECT_NEAR(eq.height_m, 20.0, 1e-6);
}

TEST(Wgs84, RoundTripManyPointsIncludingPolesAndHighAltitudes) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> lat(-90.0, 90.0), lon(-180.0, 180.0), height(-5000.0, 30.0e6);
  std::vector<wgs84::Llh> points;
  for (int i = 0; i < 2000; ++i) points.push_back({lat(rng) * kDeg, lon(rng) * kDeg, height(rng)});
  for (double la : {-90.0, -89.999999, -45.0, 0.0, 45.0, 89.999999, 90.0}) {
    for (double h : {-1000.0, 0.0, 20200e3, 36000e3}) points.push_back({la * kDeg, 33.0 * kDeg, h});
  }
  for (const auto& p : points) {
    const wgs84::Llh back = wgs84::ecef_to_llh(wgs84::llh_to_ecef(p));
    EXPECT_NEAR(back.lat_rad, p.lat_rad, 1e-9) << p.lat_rad << " " << p.height_m;
    EXPECT_NEAR(back.height_m, p.height_m, 1e-6) << p.lat_rad << " " << p.height_m;
    if (std::abs(p.lat_rad) < 89.9 * kDeg) {  // longitude is meaningless at the poles
      EXPECT_NEAR(std::remainder(back.lon_rad - p.lon_rad, 2.0 * std::numbers::pi), 0.0, 1e-9);
    }
    // The ECEF round trip checks the pole cases too.
    EXPECT_LT((wgs84::llh_to_ecef(back) - wgs84::llh_to_ecef(p)).norm(), 1e-6);
  }
}

TEST(Wgs84, RadiiOfCurvature) {
  EXPECT_NEAR(wgs84::transverse_radius_m(0.0), 6378137.0, 1e-6);
  // a (1 - e^2) at the equator; a^2 / b = a / (1 - f) at the poles (values from the defining
  // a and 1/f; tables that list 6335439.327083 and 6399593.625864 round b to 0.1 mm).
  EXPECT_NEAR(wgs84::meridian_radius_m(0.0), 6335439.3272928, 1e-6);
  EXPECT_NEAR(wgs84::transverse_radius_m(90.0 * kDeg), 6399593.6257585, 1e-6);
  EXPECT_NEAR(wgs84::meridian_radius_m(-90.0 * kDeg), 6399593.6257585, 1e-6);
  EXPECT_LT(wgs84::meridian_radius_m(37.5 * kDeg), wgs84::transverse_radius_m(37.5 * kDeg));
}

TEST(Wgs84, NormalGravity) {
  EXPECT_NEAR(wgs84::normal_gravity_mps2(0.0, 0.0), 9.7803253359, 1e-9);
  // The published polar value follows from the rounded Somigliana constant k: agreement to 1e-8.
  EXPECT_NEAR(wgs84::normal_gravity_mps2(90.0 * kDeg, 0.0), 9.8321849378, 1e-8);
  EXPECT_NEAR(wgs84::normal_gravity_mps2(-90.0 * kDeg, 0.0), 9.8321849378, 1e-8);
  // Free-air gradient is about -3.086e-6 (m/s^2)/m near the surface.
  const double g0 = wgs84::normal_gravity_mps2(45.0 * kDeg, 0.0);
  const double g1 = wgs84::normal_gravity_mps2(45.0 * kDeg, 1000.0);
  EXPECT_NEAR((g1 - g0) / 1000.0, -3.086e-6, 0.01e-6);
}

}  // namespace
}  // namespace deepnav
