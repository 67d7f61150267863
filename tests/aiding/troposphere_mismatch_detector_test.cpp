// The troposphere mismatch detector: a zenith error in the residuals is recovered whatever
// the position and clock errors are (they are nuisances), a position/clock error alone
// reads as none, and no verdict comes before the window has its fixes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "aiding/troposphere_mismatch_detector.hpp"
#include "signals/atmosphere.hpp"

namespace deepnav::aiding {
namespace {

/// Eight satellites from 8 to 80 deg elevation around the sky; residuals of a position
/// error `d_enu`, clock error `clock_m` and zenith error `zenith_m`.
std::vector<RangeResidual> sky(const Eigen::Vector3d& d_enu, double clock_m, double zenith_m) {
  std::vector<RangeResidual> out;
  const double el_deg[] = {8, 15, 25, 35, 45, 55, 68, 80};
  for (int i = 0; i < 8; ++i) {
    RangeResidual r;
    r.elevation_rad = el_deg[i] * M_PI / 180.0;
    const double az = i * 2.4;
    r.los = Eigen::Vector3d(std::cos(r.elevation_rad) * std::sin(az), std::cos(r.elevation_rad) * std::cos(az),
                            std::sin(r.elevation_rad));
    r.residual_m = -r.los.dot(d_enu) + clock_m + zenith_m * troposphere_mapping(r.elevation_rad);
    out.push_back(r);
  }
  return out;
}

TEST(TroposphereMismatchDetector, RecoversTheZenithErrorWhateverThePositionAndClock) {
  TroposphereMismatchDetector d;
  const RangeErrorModel weights;
  std::mt19937 rng(5);
  std::normal_distribution<double> metres(0.0, 5.0);
  for (int k = 0; k < 30; ++k)
    d.add(sky(Eigen::Vector3d(metres(rng), metres(rng), metres(rng)), metres(rng), -2.3), weights);
  EXPECT_NEAR(d.zenith_error_m(), -2.3, 1e-9);
  EXPECT_TRUE(d.mismatch());
}

TEST(TroposphereMismatchDetector, PositionAndClockErrorsAloneAreNoMismatch) {
  TroposphereMismatchDetector d;
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d(3.0, -2.0, 8.0), 40.0, 0.0), weights);
  EXPECT_NEAR(d.zenith_error_m(), 0.0, 1e-9);
  EXPECT_FALSE(d.mismatch());
}

TEST(TroposphereMismatchDetector, ExtraDelayIsNoMismatch) {
  // Multipath and non-line-of-sight signals add delay: a positive fit is never taken.
  TroposphereMismatchDetector d;
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, +2.3), weights);
  EXPECT_NEAR(d.zenith_error_m(), 2.3, 1e-9);
  EXPECT_FALSE(d.mismatch());
}

TEST(TroposphereMismatchDetector, NeedsItsFixesAndSixSatellites) {
  TroposphereMismatchDetector d;
  const RangeErrorModel weights;
  for (int k = 0; k < 19; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, -2.3), weights);
  EXPECT_FALSE(d.mismatch()) << "a verdict before min_fixes";
  std::vector<RangeResidual> five = sky(Eigen::Vector3d::Zero(), 0.0, -2.3);
  five.resize(5);
  d.add(five, weights);  // not counted: no redundancy for five unknowns
  EXPECT_FALSE(d.mismatch());
  d.add(sky(Eigen::Vector3d::Zero(), 0.0, -2.3), weights);
  EXPECT_TRUE(d.mismatch());
}

TEST(TroposphereMismatchDetector, FixResidualsCarryTheFixsLookAngles) {
  PvtSolution fix;
  fix.valid = true;
  fix.used_prns = {3, 7};
  fix.elevation_rad = {{3, 0.5}, {7, 1.0}};
  fix.azimuth_rad = {{3, 0.0}, {7, M_PI / 2}};
  fix.residuals_m = {{3, 1.5}, {7, -0.5}};
  const auto rows = fix_residuals(fix, {{3, 40.0}});
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NEAR(rows[0].los.y(), std::cos(0.5), 1e-12);  // north at azimuth 0
  EXPECT_NEAR(rows[1].los.x(), std::cos(1.0), 1e-12);  // east at 90 deg
  EXPECT_EQ(rows[0].cn0_dbhz, 40.0);
  EXPECT_EQ(rows[1].cn0_dbhz, 45.0);  // not given: the nominal
  EXPECT_EQ(rows[1].residual_m, -0.5);
}

}  // namespace
}  // namespace deepnav::aiding
