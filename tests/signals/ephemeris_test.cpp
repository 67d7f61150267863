#include "signals/ephemeris.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {

const NavData& brdc() {
  static const NavData nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  return nav;
}

/// Velocity in the inertial frame momentarily aligned with ECEF: v_ecef + omega_e x r.
Eigen::Vector3d inertial_velocity(const SatelliteState& s) {
  return s.v_ecef_mps + Eigen::Vector3d(0, 0, gps::kEarthRate_radps).cross(s.r_ecef_m);
}

TEST(Ephemeris, OrbitRadiusAndSpeedArePlausibleForEveryRecord) {
  double max_relativistic_s = 0.0;
  for (const Ephemeris& eph : brdc().ephemerides) {
    SCOPED_TRACE("PRN " + std::to_string(eph.prn) + " toe " + std::to_string(eph.toe_s));
    const GpsTime t = GpsTime{eph.week, eph.toe_s}.plus_seconds(3600.0);
    const SatelliteState s = satellite_state(eph, t);
    const double a = eph.sqrt_a * eph.sqrt_a;
    const double r = s.r_ecef_m.norm();
    // Within the Keplerian bounds a(1 +- e), widened by the harmonic corrections (Crs, Crc < 1 km).
    EXPECT_GT(r, a * (1.0 - eph.e) - 1000.0);
    EXPECT_LT(r, a * (1.0 + eph.e) + 1000.0);
    EXPECT_NEAR(r, 26560e3, 700e3);
    // Vis-viva speed in the inertial frame, to the few m/s the perturbations change it.
    const double v = inertial_velocity(s).norm();
    EXPECT_NEAR(v, std::sqrt(gps::kGM_m3ps2 * (2.0 / r - 1.0 / a)), 5.0);
    EXPECT_NEAR(v, 3.87e3, 0.1e3);
    // |F e sqrt(A) sin E| <= |F| e sqrt(A): under 50 ns for e < 0.02; PRN 21 (e = 0.024)
    // reaches about 53 ns in this file.
    EXPECT_LE(std::abs(s.relativistic_s), std::abs(gps::kRelativisticF) * eph.e * eph.sqrt_a * (1 + 1e-12));
    if (eph.e < 0.02) {
      EXPECT_LT(std::abs(s.relativistic_s), 50e-9);
    }
    EXPECT_LT(std::abs(s.relativistic_s), 60e-9);
    max_relativistic_s = std::max(max_relativistic_s, std::abs(s.relativistic_s));
  }
  // e up to about 0.02 makes the relativistic term reach tens of nanoseconds for some satellite.
  EXPECT_GT(max_relativistic_s, 10e-9);
}

TEST(Ephemeris, VelocityAndClockDriftMatchFiniteDifferences) {
  for (std::size_t i = 0; i < brdc().ephemerides.size(); i += 7) {
    const Ephemeris& eph = brdc().ephemerides[i];
    SCOPED_TRACE("PRN " + std::to_string(eph.prn));
    for (double dt : {-7000.0, -100.0, 0.0, 2500.0, 7100.0}) {
      const GpsTime t = GpsTime{eph.week, eph.toe_s}.plus_seconds(dt);
      const double h = 0.5;
      const SatelliteState s = satellite_state(eph, t);
      const SatelliteState before = satellite_state(eph, t.plus_seconds(-h));
      const SatelliteState after = satellite_state(eph, t.plus_seconds(h));
      const Eigen::Vector3d v_fd = (after.r_ecef_m - before.r_ecef_m) / (2 * h);
      EXPECT_LT((s.v_ecef_mps - v_fd).norm(), 1e-3) << s.v_ecef_mps.transpose() << " vs " << v_fd.transpose();
      const double drift_fd = (after.clock_bias_s - before.clock_bias_s) / (2 * h);
      EXPECT_NEAR(s.clock_drift_sps, drift_fd, 1e-15);
    }
  }
}

TEST(Ephemeris, ClockModelTerms) {
  Ephemeris eph = brdc().ephemerides.front();
  eph.af2_sps2 = 1e-18;
  const GpsTime t{eph.week, eph.toc_s + 1000.0};
  const SatelliteState s = satellite_state(eph, t);
  EXPECT_NEAR(s.clock_bias_s - s.relativistic_s, eph.af0_s + eph.af1_sps * 1000.0 + 1e-18 * 1e6, 1e-18);
  EXPECT_DOUBLE_EQ(l1_clock_correction_s(eph, t), s.clock_bias_s - eph.tgd_s);
  // A circular orbit has no relativistic clock term.
  eph.e = 0.0;
  EXPECT_EQ(satellite_state(eph, t).relativistic_s, 0.0);
}

TEST(Ephemeris, ContinuousAcrossTheWeekBoundary) {
  // PRN 32's last data set has toe = 604784 s of week 2190; it stays valid into week 2191.
  const Ephemeris& eph = brdc().ephemerides.back();
  ASSERT_DOUBLE_EQ(eph.toe_s, 604784.0);
  const SatelliteState before = satellite_state(eph, GpsTime{2190, 604799.5});
  const SatelliteState after = satellite_state(eph, GpsTime{2191, 0.5});
  const Eigen::Vector3d predicted = before.r_ecef_m + 0.5 * (before.v_ecef_mps + after.v_ecef_mps);
  EXPECT_LT((after.r_ecef_m - predicted).norm(), 1e-3);
  EXPECT_NEAR(after.clock_bias_s - before.clock_bias_s, before.clock_drift_sps, 1e-15);
  // Same result when the week is not known (only the seconds-of-week fold is available).
  Ephemeris no_week = eph;
  no_week.week = 0;
  EXPECT_LT((satellite_state(no_week, GpsTime{2191, 0.5}).r_ecef_m - after.r_ecef_m).norm(), 1e-6);
  // Weeks more than half a week apart are taken as unreliable (e.g. a 1024-week rollover):
  // the seconds-of-week fold applies, as with an unknown week.
  const GpsTime at_toe{2190, 604784.0};
  EXPECT_LT(
      (satellite_state(eph, GpsTime{2190 + 1024, 604784.0}).r_ecef_m - satellite_state(eph, at_toe).r_ecef_m).norm(),
      1e-6);
}

TEST(Ephemeris, KeplerEquationConvergesForLargeEccentricity) {
  // The orbit radius a (1 - e cos E) must match the position norm without harmonic terms.
  Ephemeris eph = brdc().ephemerides.front();
  eph.crc_m = eph.crs_m = eph.cuc_rad = eph.cus_rad = eph.cic_rad = eph.cis_rad = 0.0;
  for (double e : {0.0, 0.02, 0.3, 0.7}) {
    eph.e = e;
    for (double dt = 0.0; dt < 43200.0; dt += 3517.0) {
      const SatelliteState s = satellite_state(eph, GpsTime{eph.week, eph.toe_s}.plus_seconds(dt));
      const double a = eph.sqrt_a * eph.sqrt_a;
      // E from the relativistic term: sin E = dtr / (F e sqrt(A)); radius from r = a(1 - e cos E).
      const double r = s.r_ecef_m.norm();
      const double cos_e = (1.0 - r / a) / (e > 0 ? e : 1.0);
      const double sin_e = e > 0 ? s.relativistic_s / (gps::kRelativisticF * e * eph.sqrt_a) : 0.0;
      if (e > 0) {
        EXPECT_NEAR(cos_e * cos_e + sin_e * sin_e, 1.0, 1e-6) << "e " << e << " dt " << dt;
      }
      const double n = std::sqrt(gps::kGM_m3ps2 / (a * a * a)) + eph.delta_n_radps;
      const double ecc = std::atan2(sin_e, cos_e);
      const double m = eph.m0_rad + n * dt;
      if (e > 0) {
        EXPECT_NEAR(std::remainder(ecc - e * std::sin(ecc) - m, 2 * std::numbers::pi), 0.0, 1e-7);
      }
    }
  }
}

TEST(Ephemeris, EarthRotationCorrection) {
  const Eigen::Vector3d r(26560e3, 0.0, 1000.0);
  const double tau = 0.075;
  const Eigen::Vector3d rot = earth_rotation_corrected(r, tau);
  EXPECT_NEAR(rot.norm(), r.norm(), 1e-6);
  EXPECT_DOUBLE_EQ(rot.z(), 1000.0);
  // The Earth turns east by omega tau; the satellite appears that much to the west (-y).
  EXPECT_NEAR(rot.y(), -26560e3 * gps::kEarthRate_radps * tau, 1e-3);
  EXPECT_LT(rot.y(), -140.0);
  EXPECT_TRUE(earth_rotation_corrected(r, 0.0).isApprox(r));
}

TEST(Ephemeris, FitInterval) {
  Ephemeris eph;
  EXPECT_DOUBLE_EQ(fit_interval_s(eph), 4 * 3600.0);
  eph.fit_interval_flag = 1;
  eph.iodc = 100;
  EXPECT_DOUBLE_EQ(fit_interval_s(eph), 6 * 3600.0);
  eph.iodc = 250;
  EXPECT_DOUBLE_EQ(fit_interval_s(eph), 14 * 3600.0);
  eph.iodc = 757;
  EXPECT_DOUBLE_EQ(fit_interval_s(eph), 98 * 3600.0);
}

}  // namespace
}  // namespace deepnav
