#include "ins/frames.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <numbers>

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Frames, RotationIsOrthonormalAndRightHanded) {
  for (double lat : {-90.0, -37.0, 0.0, 37.5, 89.0, 90.0}) {
    for (double lon : {-180.0, -10.0, 0.0, 127.0}) {
      const Eigen::Matrix3d c = C_n_e(lat * kDeg, lon * kDeg);
      EXPECT_TRUE((c.transpose() * c).isIdentity(1e-14));
      EXPECT_NEAR(c.determinant(), 1.0, 1e-14);
      EXPECT_TRUE(C_e_n(lat * kDeg, lon * kDeg).isApprox(c.transpose(), 0.0));
    }
  }
  // At (0, 0): north is +z, east is +y, down is -x.
  const Eigen::Matrix3d c = C_n_e(0.0, 0.0);
  EXPECT_TRUE(c.col(0).isApprox(Eigen::Vector3d::UnitZ(), 1e-15));
  EXPECT_TRUE(c.col(1).isApprox(Eigen::Vector3d::UnitY(), 1e-15));
  EXPECT_TRUE(c.col(2).isApprox(-Eigen::Vector3d::UnitX(), 1e-15));
}

TEST(Frames, DownIsTheEllipsoidNormal) {
  // Moving along "down" lowers the height and keeps latitude/longitude.
  const wgs84::Llh p{37.5 * kDeg, 127.0 * kDeg, 50.0};
  const Eigen::Vector3d r = wgs84::llh_to_ecef(p) + ned_to_ecef_vector(p, {0.0, 0.0, 30.0});
  const wgs84::Llh q = wgs84::ecef_to_llh(r);
  EXPECT_NEAR(q.lat_rad, p.lat_rad, 1e-12);
  EXPECT_NEAR(q.lon_rad, p.lon_rad, 1e-12);
  EXPECT_NEAR(q.height_m, 20.0, 1e-6);
  const Eigen::Vector3d v(1.0, -2.0, 3.0);
  EXPECT_TRUE(ecef_to_ned_vector(p, ned_to_ecef_vector(p, v)).isApprox(v, 1e-14));
}

TEST(Frames, NedOffsetOfAPointToTheNorth) {
  const wgs84::Llh a{37.5 * kDeg, 127.0 * kDeg, 50.0};
  const double dlat = 100.0 / (wgs84::meridian_radius_m(a.lat_rad) + a.height_m);
  const wgs84::Llh b{a.lat_rad + dlat, a.lon_rad, a.height_m};
  const Eigen::Vector3d d = ned_offset_m(wgs84::llh_to_ecef(a), wgs84::llh_to_ecef(b));
  EXPECT_NEAR(d.x(), 100.0, 1e-3);
  EXPECT_NEAR(d.y(), 0.0, 1e-9);
  EXPECT_NEAR(d.z(), 100.0 * 100.0 / (2.0 * 6.36e6), 2e-4);  // the ellipsoid curves away below the horizon
  const double dlon = 50.0 / ((wgs84::transverse_radius_m(a.lat_rad) + a.height_m) * std::cos(a.lat_rad));
  const Eigen::Vector3d e =
      ned_offset_m(wgs84::llh_to_ecef(a), wgs84::llh_to_ecef({a.lat_rad, a.lon_rad + dlon, a.height_m}));
  EXPECT_NEAR(e.y(), 50.0, 1e-3);
  EXPECT_GT(e.z(), 0.0);
}

TEST(Frames, EarthRate) {
  const Eigen::Vector3d w = earth_rate_ned_radps(35.0 * kDeg);
  EXPECT_NEAR(w.norm(), wgs84::kEarthRate_radps, 1e-18);
  EXPECT_NEAR(w.x(), wgs84::kEarthRate_radps * std::cos(35.0 * kDeg), 1e-18);
  EXPECT_EQ(w.y(), 0.0);
  EXPECT_LT(w.z(), 0.0);  // points up in the northern hemisphere
  // Same vector as the ECEF z axis rotated into NED.
  const Eigen::Vector3d w_e = wgs84::kEarthRate_radps * Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(ecef_to_ned_vector({35.0 * kDeg, 20.0 * kDeg, 0.0}, w_e).isApprox(w, 1e-14));
}

TEST(Frames, TransportRateMatchesTheRotationOfNedAlongAPath) {
  // Move along a smooth ECEF path; the NED frame at the moving point must satisfy
  // C_n_e' = C_n_e [w_en_n x], and d(w_en_n)/dt must match its finite difference.
  const Eigen::Vector3d r0 = wgs84::llh_to_ecef({37.5 * kDeg, 127.0 * kDeg, 3000.0});
  const auto r_at = [&](double t) {
    return Eigen::Vector3d(r0 + Eigen::Vector3d(150.0 * t + 2.0 * t * t, -80.0 * t, 60.0 * t - 1.5 * t * t));
  };
  const auto v_at = [](double t) { return Eigen::Vector3d(150.0 + 4.0 * t, -80.0, 60.0 - 3.0 * t); };
  const Eigen::Vector3d a_e(4.0, 0.0, -3.0);
  const auto w_at = [&](double t) {
    const wgs84::Llh p = wgs84::ecef_to_llh(r_at(t));
    return transport_rate_ned_radps(p, ecef_to_ned_vector(p, v_at(t)));
  };
  const double h = 1e-2;
  for (double t : {0.0, 10.0, 50.0}) {
    const wgs84::Llh p = wgs84::ecef_to_llh(r_at(t));
    const wgs84::Llh pp = wgs84::ecef_to_llh(r_at(t + h)), pm = wgs84::ecef_to_llh(r_at(t - h));
    const Eigen::Matrix3d dc = (C_n_e(pp.lat_rad, pp.lon_rad) - C_n_e(pm.lat_rad, pm.lon_rad)) / (2.0 * h);
    const Eigen::Matrix3d s = C_e_n(p.lat_rad, p.lon_rad) * dc;
    const Eigen::Vector3d w_fd(s(2, 1), s(0, 2), s(1, 0));
    const Eigen::Vector3d w = w_at(t);
    EXPECT_LT((w - w_fd).norm(), 1e-9 * w.norm()) << t;

    const Eigen::Vector3d v_n = ecef_to_ned_vector(p, v_at(t));
    const Eigen::Vector3d a_n = ecef_to_ned_vector(p, a_e) - w.cross(v_n);  // derivative of NED components
    const Eigen::Vector3d dw = transport_rate_derivative_ned_radps2(p, v_n, a_n);
    const Eigen::Vector3d dw_fd = (w_at(t + h) - w_at(t - h)) / (2.0 * h);
    EXPECT_LT((dw - dw_fd).norm(), 1e-6 * dw.norm()) << t;
  }
}

TEST(Frames, LookAngles) {
  const wgs84::Llh rx{37.5 * kDeg, 127.0 * kDeg, 50.0};
  const Eigen::Vector3d r = wgs84::llh_to_ecef(rx);
  const LookAngles up = look_angles(r, wgs84::llh_to_ecef({rx.lat_rad, rx.lon_rad, 20000e3}));
  EXPECT_NEAR(up.elevation_rad, 90.0 * kDeg, 1e-9);
  const LookAngles down = look_angles(r, wgs84::llh_to_ecef({rx.lat_rad, rx.lon_rad, -100.0}));
  EXPECT_NEAR(down.elevation_rad, -90.0 * kDeg, 1e-9);
  // Along the local axes: 30 deg elevation to the east, 10 deg to the north-west.
  const auto toward = [&](double el_deg, double az_deg) {
    const double el = el_deg * kDeg, az = az_deg * kDeg;
    const Eigen::Vector3d los_n(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el));
    return Eigen::Vector3d(r + ned_to_ecef_vector(rx, 2.0e7 * los_n));
  };
  const LookAngles east = look_angles(r, toward(30.0, 90.0));
  EXPECT_NEAR(east.elevation_rad, 30.0 * kDeg, 1e-12);
  EXPECT_NEAR(east.azimuth_rad, 90.0 * kDeg, 1e-12);
  const LookAngles nw = look_angles(rx, r, toward(10.0, 315.0));
  EXPECT_NEAR(nw.elevation_rad, 10.0 * kDeg, 1e-12);
  EXPECT_NEAR(nw.azimuth_rad, 315.0 * kDeg, 1e-12);
  EXPECT_THROW(look_angles(r, r), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
