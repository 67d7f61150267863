#include "signals/atmosphere.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ins/wgs84.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMidnightSow = 518400.0;  // 2022-01-01 00:00 GPS (Saturday)

/// Broadcast values of data/brdc0010.22n.
IonoParameters brdc_iono() {
  IonoParameters p;
  p.alpha = {0.1211e-07, -0.7451e-08, -0.5960e-07, 0.1192e-06};
  p.beta = {0.1167e+06, -0.2458e+06, -0.6554e+05, 0.1114e+07};
  p.valid = true;
  return p;
}

/// Satellite 20,000 km away in the direction (azimuth, elevation) from a receiver.
Eigen::Vector3d satellite_at(const wgs84::Llh& rx, double az, double el) {
  const double sl = std::sin(rx.lat_rad), cl = std::cos(rx.lat_rad);
  const double so = std::sin(rx.lon_rad), co = std::cos(rx.lon_rad);
  const Eigen::Vector3d east(-so, co, 0.0), north(-sl * co, -sl * so, cl), up(cl * co, cl * so, sl);
  const Eigen::Vector3d u = std::cos(el) * (std::sin(az) * east + std::cos(az) * north) + std::sin(el) * up;
  return wgs84::llh_to_ecef(rx) + 20000e3 * u;
}

TEST(Klobuchar, MatchesIndependentEvaluation) {
  // Reference values from a separate evaluation of IS-GPS-200 Figure 20-4 (double precision).
  const IonoParameters p = brdc_iono();
  EXPECT_NEAR(klobuchar_delay_s(p, 36.37 * kDeg, 127.36 * kDeg, 135 * kDeg, 30 * kDeg, kMidnightSow + 5 * 3600),
              2.739673688231056e-08, 1e-17);
  EXPECT_NEAR(klobuchar_delay_s(p, 36.37 * kDeg, 127.36 * kDeg, 0.0, 90 * kDeg, kMidnightSow + 5 * 3600),
              1.5117473455952453e-08, 1e-17);
  EXPECT_NEAR(klobuchar_delay_s(p, -33.9 * kDeg, 18.4 * kDeg, 300 * kDeg, 15 * kDeg, kMidnightSow + 12 * 3600),
              3.9340963693711056e-08, 1e-17);
  EXPECT_NEAR(klobuchar_delay_m(p, 36.37 * kDeg, 127.36 * kDeg, 135 * kDeg, 30 * kDeg, kMidnightSow + 5 * 3600),
              2.739673688231056e-08 * gps::kSpeedOfLight_mps, 1e-8);
}

TEST(Klobuchar, NightTimeIsTheFiveNanosecondConstant) {
  // Korea at 02:00 local time (17:00 UT): outside the cosine's daytime half period.
  const double t = kMidnightSow + 17 * 3600;
  const double zenith = klobuchar_delay_s(brdc_iono(), 36.37 * kDeg, 127.36 * kDeg, 0.0, 90 * kDeg, t);
  const double obliquity_at_zenith = 1.0 + 16.0 * std::pow(0.53 - 0.5, 3);
  EXPECT_NEAR(zenith, 5e-9 * obliquity_at_zenith, 1e-18);
  // Low satellites see the same constant times the obliquity factor.
  const double el = 10 * kDeg;
  const double low = klobuchar_delay_s(brdc_iono(), 36.37 * kDeg, 127.36 * kDeg, 200 * kDeg, el, t);
  EXPECT_NEAR(low, 5e-9 * (1.0 + 16.0 * std::pow(0.53 - el / gps::kPi, 3)), 1e-18);
}

TEST(Klobuchar, PlausibleRangeOverADay) {
  const IonoParameters p = brdc_iono();
  double max_m = 0.0;
  int cases = 0, low_longer = 0;
  for (double lat : {-60.0, -20.0, 0.0, 36.37, 70.0}) {
    for (double hour = 0; hour < 24; hour += 1.5) {
      for (double az = 0; az < 360; az += 45) {
        for (double el : {90.0, 60.0, 30.0, 15.0, 10.0}) {
          const double d =
              klobuchar_delay_m(p, lat * kDeg, 127.0 * kDeg, az * kDeg, el * kDeg, kMidnightSow + hour * 3600);
          EXPECT_GT(d, 1.0);
          EXPECT_LT(d, 30.0);
          max_m = std::max(max_m, d);
        }
        // Lower satellites see a longer path, except where their pierce point lies in a
        // region with a much smaller vertical delay (near the day/night boundary).
        const double t = kMidnightSow + hour * 3600;
        ++cases;
        if (klobuchar_delay_m(p, lat * kDeg, 127.0 * kDeg, az * kDeg, 10 * kDeg, t) >
            klobuchar_delay_m(p, lat * kDeg, 127.0 * kDeg, az * kDeg, 90 * kDeg, t)) {
          ++low_longer;
        }
      }
    }
  }
  EXPECT_GT(low_longer, cases * 95 / 100);
  EXPECT_GT(max_m, 8.0);  // the daytime peak is well above the night floor
}

TEST(Klobuchar, EcefOverloadUsesLookAngles) {
  const IonoParameters p = brdc_iono();
  const wgs84::Llh rx{36.37 * kDeg, 127.36 * kDeg, 80.0};
  const double t = kMidnightSow + 5 * 3600;
  for (double az : {10.0, 135.0, 250.0}) {
    for (double el : {12.0, 45.0, 80.0}) {
      const Eigen::Vector3d sat = satellite_at(rx, az * kDeg, el * kDeg);
      EXPECT_NEAR(klobuchar_delay_m(p, wgs84::llh_to_ecef(rx), sat, t),
                  klobuchar_delay_m(p, rx.lat_rad, rx.lon_rad, az * kDeg, el * kDeg, t), 1e-6);
    }
  }
}

TEST(Klobuchar, RejectsMissingParameters) {
  IonoParameters p = brdc_iono();
  p.valid = false;
  EXPECT_THROW(klobuchar_delay_s(p, 0.5, 0.5, 0.0, 0.5, 0.0), std::invalid_argument);
}

TEST(Troposphere, ZenithDelayAtSeaLevel) {
  const TroposphereZenithDelay z = saastamoinen_zenith_delay(45 * kDeg, 0.0);
  // 0.0022768 * 1013.25 hPa; wet part from 70 % humidity at 15 degC.
  EXPECT_NEAR(z.hydrostatic_m, 2.3069676, 1e-6);
  EXPECT_NEAR(z.wet_m, 0.1204141, 1e-6);
  EXPECT_GT(z.total_m(), 2.3);
  EXPECT_LT(z.total_m(), 2.5);
  EXPECT_NEAR(troposphere_delay_m(45 * kDeg, 0.0, 90 * kDeg), z.total_m(), 1e-3);
}

TEST(Troposphere, DecreasesWithHeight) {
  double previous = 1e9;
  for (double h : {-400.0, 0.0, 1000.0, 3000.0, 8000.0, 11000.0, 15000.0, 30000.0}) {
    const double d = saastamoinen_zenith_delay(36 * kDeg, h).total_m();
    EXPECT_LT(d, previous) << h;
    EXPECT_GT(d, 0.0);
    previous = d;
  }
  // About 1.85 m at 2 km, roughly 0.3 m in the lower stratosphere.
  EXPECT_NEAR(saastamoinen_zenith_delay(36 * kDeg, 2000.0).total_m(), 1.85, 0.1);
  EXPECT_LT(saastamoinen_zenith_delay(36 * kDeg, 15000.0).total_m(), 0.4);
}

TEST(Troposphere, MappingGrowsLikeOneOverSineOfElevation) {
  EXPECT_NEAR(troposphere_mapping(90 * kDeg), 1.0, 1e-6);
  for (double el : {15.0, 30.0, 45.0, 60.0}) {
    EXPECT_NEAR(troposphere_mapping(el * kDeg) * std::sin(el * kDeg), 1.0, 0.02) << el;
  }
  EXPECT_NEAR(troposphere_mapping(30 * kDeg), 2.0, 0.02);
  // Finite at and below the horizon, where 1/sin(el) diverges.
  EXPECT_NEAR(troposphere_mapping(0.0), 1.001 / std::sqrt(0.002001), 1e-9);
  EXPECT_DOUBLE_EQ(troposphere_mapping(-5 * kDeg), troposphere_mapping(0.0));
  double previous = 0.0;
  for (double el = 90.0; el >= 0.0; el -= 5.0) {
    EXPECT_GT(troposphere_mapping(el * kDeg), previous);
    previous = troposphere_mapping(el * kDeg);
  }
}

TEST(Troposphere, EcefOverload) {
  const wgs84::Llh rx{36.37 * kDeg, 127.36 * kDeg, 80.0};
  const Eigen::Vector3d r = wgs84::llh_to_ecef(rx);
  EXPECT_NEAR(troposphere_delay_m(r, satellite_at(rx, 0.0, 90 * kDeg)),
              saastamoinen_zenith_delay(rx.lat_rad, 80.0).total_m(), 1e-6);
  EXPECT_NEAR(troposphere_delay_m(r, satellite_at(rx, 77 * kDeg, 20 * kDeg)),
              troposphere_delay_m(rx.lat_rad, 80.0, 20 * kDeg), 1e-6);
  EXPECT_THROW(troposphere_delay_m(r, r), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
