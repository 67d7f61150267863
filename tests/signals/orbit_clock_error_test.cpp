#include "signals/sim/orbit_clock_error.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

#include "signals/sim/error_presets.hpp"

namespace deepnav {
namespace {

const GpsTime kStart{2190, 518400.0 + 7200.0};

OrbitClockError open_sky(std::uint64_t seed, double duration_s) {
  return OrbitClockError(error_preset("open-sky").orbit_clock, seed, kStart, duration_s);
}

TEST(OrbitClockError, NoneIsExactlyZero) {
  const OrbitClockError none(OrbitClockErrorSpec{}, 1, kStart, 600.0);
  EXPECT_FALSE(none.active());
  const OrbitClockErrorSample s = none.at(5, kStart.plus_seconds(100.0));
  EXPECT_EQ(s.rac_m, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.clock_m, 0.0);
}

TEST(OrbitClockError, ComponentsAndSisreHaveTheConfiguredSizes) {
  const OrbitClockErrorSpec spec = error_preset("open-sky").orbit_clock;
  EXPECT_NEAR(spec.global_average_sisre_m(), 0.60, 0.01);
  // 32 satellites over a day: ~24 correlation times each.
  const OrbitClockError e = open_sky(11, 86400.0);
  Eigen::Vector4d sum2 = Eigen::Vector4d::Zero();
  double sisre2 = 0.0;
  int n = 0;
  for (int prn = 1; prn <= 32; ++prn) {
    for (int s = 0; s <= 86400; s += 300) {
      const OrbitClockErrorSample x = e.at(prn, kStart.plus_seconds(s));
      sum2 += Eigen::Vector4d(x.rac_m.x(), x.rac_m.y(), x.rac_m.z(), x.clock_m).cwiseAbs2();
      sisre2 += std::pow(x.rac_m.x() - x.clock_m, 2) + (x.rac_m.y() * x.rac_m.y() + x.rac_m.z() * x.rac_m.z()) / 49.0;
      ++n;
    }
  }
  const Eigen::Vector4d rms = (sum2 / n).cwiseSqrt();
  std::printf("open-sky broadcast errors RMS: radial %.3f along %.3f cross %.3f clock %.3f m, SISRE %.3f m\n", rms(0),
              rms(1), rms(2), rms(3), std::sqrt(sisre2 / n));
  EXPECT_NEAR(rms(0), spec.radial_m, 0.15 * spec.radial_m);
  EXPECT_NEAR(rms(1), spec.along_m, 0.15 * spec.along_m);
  EXPECT_NEAR(rms(2), spec.cross_m, 0.15 * spec.cross_m);
  EXPECT_NEAR(rms(3), spec.clock_m, 0.15 * spec.clock_m);
  EXPECT_NEAR(std::sqrt(sisre2 / n), spec.global_average_sisre_m(), 0.1);
}

TEST(OrbitClockError, CorrelatedOverTheCorrelationTimeAndSmooth) {
  const OrbitClockError e = open_sky(3, 86400.0);
  // Autocorrelation of the clock at lags of 1 min and of the correlation time (1 h).
  double c0 = 0.0, c_min = 0.0, c_tau = 0.0;
  for (int prn = 1; prn <= 32; ++prn) {
    for (int s = 0; s + 3600 <= 86400; s += 600) {
      const double x = e.at(prn, kStart.plus_seconds(s)).clock_m;
      c0 += x * x;
      c_min += x * e.at(prn, kStart.plus_seconds(s + 60)).clock_m;
      c_tau += x * e.at(prn, kStart.plus_seconds(s + 3600)).clock_m;
    }
  }
  EXPECT_GT(c_min / c0, 0.95);
  EXPECT_NEAR(c_tau / c0, std::exp(-1.0), 0.15);
  // Between milliseconds the value moves by well under a millimetre (no steps at the nodes).
  double largest_step = 0.0;
  for (int ms = 0; ms < 200000; ++ms) {
    const double a = e.at(7, kStart.plus_seconds(ms * 1e-3)).rac_m.y();
    const double b = e.at(7, kStart.plus_seconds(ms * 1e-3 + 1e-3)).rac_m.y();
    largest_step = std::max(largest_step, std::abs(b - a));
  }
  EXPECT_LT(largest_step, 1e-4);
}

TEST(OrbitClockError, SeededPerSatellite) {
  const OrbitClockError a = open_sky(21, 3600.0), b = open_sky(21, 3600.0), c = open_sky(22, 3600.0);
  // A longer run draws the same values over the common span (each PRN has its own stream).
  const OrbitClockError longer = open_sky(21, 7200.0);
  for (int prn : {1, 9, 32}) {
    for (int s : {0, 77, 1800, 3599}) {
      const GpsTime t = kStart.plus_seconds(s);
      EXPECT_EQ(a.at(prn, t).rac_m, b.at(prn, t).rac_m);
      EXPECT_EQ(a.at(prn, t).clock_m, b.at(prn, t).clock_m);
      EXPECT_EQ(a.at(prn, t).clock_m, longer.at(prn, t).clock_m);
      EXPECT_NE(a.at(prn, t).clock_m, c.at(prn, t).clock_m);
    }
  }
  EXPECT_NE(a.at(1, kStart).clock_m, a.at(2, kStart).clock_m);
}

TEST(OrbitClockError, RacFrameIsOrthonormalAndRadialIsUp) {
  const Eigen::Vector3d r(15600e3, 7540e3, 20140e3);
  const Eigen::Vector3d v(-2600.0, 1800.0, 1400.0);
  const Eigen::Matrix3d m = rac_to_ecef(r, v);
  EXPECT_TRUE((m.transpose() * m).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_NEAR(m.determinant(), 1.0, 1e-12);
  EXPECT_TRUE(m.col(0).isApprox(r.normalized(), 1e-12));
  EXPECT_GT(m.col(1).dot(v), 0.0);  // along-track points the way the satellite moves
  EXPECT_NEAR(m.col(2).dot(v), 0.0, 1e-9);
}

}  // namespace
}  // namespace deepnav
