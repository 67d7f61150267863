// The delay mismatch detector: a zenith error in the residuals is recovered whatever
// the position and clock errors are (they are nuisances), a position/clock error alone
// reads as none, and no verdict comes before the window has its fixes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "aiding/delay_mismatch_detector.hpp"
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

TEST(DelayMismatchDetector, RecoversTheZenithErrorWhateverThePositionAndClock) {
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  std::mt19937 rng(5);
  std::normal_distribution<double> metres(0.0, 5.0);
  for (int k = 0; k < 30; ++k)
    d.add(sky(Eigen::Vector3d(metres(rng), metres(rng), metres(rng)), metres(rng), -2.3), weights);
  EXPECT_NEAR(d.fitted_error(), -2.3, 1e-9);
  EXPECT_TRUE(d.mismatch());
}

TEST(DelayMismatchDetector, PositionAndClockErrorsAloneAreNoMismatch) {
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d(3.0, -2.0, 8.0), 40.0, 0.0), weights);
  EXPECT_NEAR(d.fitted_error(), 0.0, 1e-9);
  EXPECT_FALSE(d.mismatch());
}

TEST(DelayMismatchDetector, ExtraDelayIsNoMismatch) {
  // Multipath and non-line-of-sight signals add delay: a positive fit is never taken.
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, +2.3), weights);
  EXPECT_NEAR(d.fitted_error(), 2.3, 1e-9);
  EXPECT_FALSE(d.mismatch());
}

TEST(DelayMismatchDetector, AnErrorNoSignalCouldShowIsNoMismatch) {
  // A consistent zenith fit of -10 m: more than any troposphere model's whole delay.
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, -10.0 + noise(rng)), weights);
  EXPECT_NEAR(d.fitted_error(), -10.0, 0.3);
  EXPECT_LT(d.consistency(), -DelayMismatchConfig{}.min_consistency) << "the fixes agree";
  EXPECT_FALSE(d.mismatch());
}

TEST(DelayMismatchDetector, OneWildFixIsLeftOutOfTheWindow) {
  // 29 fixes without error and one whose residuals fit -2000 m at the zenith (a fix gone
  // wrong): the window keeps reading no error.
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, k == 15 ? -2000.0 : 0.01 * (k % 3)), weights);
  EXPECT_NEAR(d.fitted_error(), 0.01, 0.01);
  EXPECT_FALSE(d.mismatch());
}

TEST(DelayMismatchDetector, AMissingDelayIsFoundThroughFixToFixNoise) {
  // Each fix reads -2.3 m with 0.4 m of its own noise (as the circles without troposphere
  // do): consistent, so a mismatch.
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  std::mt19937 rng(11);
  std::normal_distribution<double> fix_noise(0.0, 0.4);
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, -2.3 + fix_noise(rng)), weights);
  EXPECT_NEAR(d.fitted_error(), -2.3, 0.2);
  EXPECT_LT(d.consistency(), -20.0);
  EXPECT_TRUE(d.mismatch());
}

TEST(DelayMismatchDetector, FixesThatDisagreeAreNoMismatchWhateverTheirMean) {
  // Errors that swing from fix to fix (multipath in a street): the window's mean is past
  // the threshold, but the fixes do not agree on it, so no verdict.
  DelayMismatchDetector d;
  const RangeErrorModel weights;
  const double swings[] = {-4.5, 1.5, -3.9, 0.5, -5.2, 2.4};
  for (int k = 0; k < 30; ++k) d.add(sky(Eigen::Vector3d::Zero(), 0.0, swings[k % 6]), weights);
  EXPECT_LT(d.fitted_error(), -1.5);
  EXPECT_GT(d.consistency(), -6.0);
  EXPECT_FALSE(d.mismatch());
}

TEST(DelayMismatchDetector, NeedsItsFixesAndSixSatellites) {
  DelayMismatchDetector d;
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

TEST(DelayMismatchDetector, FixResidualsCarryTheFixsLookAngles) {
  PvtSolution fix;
  fix.valid = true;
  const SatelliteId g3{GnssSystem::gps, 3}, g7{GnssSystem::gps, 7};
  fix.used_satellites = {g3, g7};
  fix.elevation_rad = {{g3, 0.5}, {g7, 1.0}};
  fix.azimuth_rad = {{g3, 0.0}, {g7, M_PI / 2}};
  fix.residuals_m = {{g3, 1.5}, {g7, -0.5}};
  fix.ionosphere_m = {{g3, 7.0}};
  const auto rows = fix_residuals(fix, {{3, 40.0}});
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NEAR(rows[0].los.y(), std::cos(0.5), 1e-12);  // north at azimuth 0
  EXPECT_NEAR(rows[1].los.x(), std::cos(1.0), 1e-12);  // east at 90 deg
  EXPECT_EQ(rows[0].cn0_dbhz, 40.0);
  EXPECT_EQ(rows[1].cn0_dbhz, 45.0);  // not given: the nominal
  EXPECT_EQ(rows[1].residual_m, -0.5);
  EXPECT_EQ(rows[0].ionosphere_model_m, 7.0);
  EXPECT_EQ(rows[1].ionosphere_model_m, 0.0);  // no model delay applied
}

/// The same sky with an ionosphere model of 4 m at the zenith (Klobuchar's obliquity
/// factor) and residuals of that delay scaled by `scale`, plus position and clock errors.
std::vector<RangeResidual> ionosphere_sky(const Eigen::Vector3d& d_enu, double clock_m, double scale,
                                          double zenith_m = 0.0) {
  std::vector<RangeResidual> out = sky(d_enu, clock_m, zenith_m);
  for (RangeResidual& r : out) {
    const double f = 1.0 + 16.0 * std::pow(0.53 - r.elevation_rad / M_PI, 3);
    r.ionosphere_model_m = 4.0 * f;
    r.residual_m += scale * r.ionosphere_model_m;
  }
  return out;
}

TEST(DelayMismatchDetector, IonosphereSignatureRecoversTheModelsScaleError) {
  const DelayMismatchConfig cfg{.signature = DelaySignature::ionosphere_scale, .threshold = 0.75};
  DelayMismatchDetector missing(cfg), weak(cfg);
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) {
    // The signal without ionosphere: the model's whole delay is too much (scale -1).
    missing.add(ionosphere_sky(Eigen::Vector3d(2.0, -1.0, 6.0), 25.0, -1.0), weights);
    // A model that leaves 40 % of the delay out: an ordinary Klobuchar error.
    weak.add(ionosphere_sky(Eigen::Vector3d(2.0, -1.0, 6.0), 25.0, 0.4), weights);
  }
  EXPECT_NEAR(missing.fitted_error(), -1.0, 1e-9);
  EXPECT_TRUE(missing.mismatch());
  EXPECT_NEAR(weak.fitted_error(), 0.4, 1e-9);
  EXPECT_FALSE(weak.mismatch());
}

TEST(DelayMismatchDetector, ANegativeIonosphereIsNoMismatch) {
  // The receiver's watch: a scale below -1.75 would make the signal's delay negative.
  const DelayMismatchConfig cfg{
      .signature = DelaySignature::ionosphere_scale, .threshold = 0.75, .plausible_floor = -1.75};
  DelayMismatchDetector none(cfg), negative(cfg);
  const RangeErrorModel weights;
  for (int k = 0; k < 30; ++k) {
    none.add(ionosphere_sky(Eigen::Vector3d(2.0, -1.0, 6.0), 25.0, -1.0 + 0.01 * (k % 5)), weights);
    negative.add(ionosphere_sky(Eigen::Vector3d(2.0, -1.0, 6.0), 25.0, -3.0 + 0.01 * (k % 5)), weights);
  }
  EXPECT_TRUE(none.mismatch());
  EXPECT_NEAR(negative.fitted_error(), -2.98, 0.01);
  EXPECT_FALSE(negative.mismatch());
}

TEST(DelayMismatchDetector, TheIonosphereBesideTheTroposphereIsToldApart) {
  // The signal lacks both delays: the troposphere's fit alone takes part of the ionosphere's
  // (its signature looks alike); fitted beside the troposphere's error the ionosphere's
  // scale comes out whole, and with the troposphere alone missing it reads none.
  const DelayMismatchConfig single{.signature = DelaySignature::ionosphere_scale, .threshold = 0.75};
  DelayMismatchConfig beside = single;
  beside.also_fitted = DelaySignature::troposphere_zenith;
  DelayMismatchDetector troposphere_alone, both_single(single), both_beside(beside), none_beside(beside);
  const RangeErrorModel weights;
  const Eigen::Vector3d d_enu(2.0, -1.0, 6.0);
  for (int k = 0; k < 30; ++k) {
    troposphere_alone.add(ionosphere_sky(d_enu, 25.0, -1.0, -2.3), weights);
    both_single.add(ionosphere_sky(d_enu, 25.0, -1.0, -2.3), weights);
    both_beside.add(ionosphere_sky(d_enu, 25.0, -1.0, -2.3), weights);
    none_beside.add(ionosphere_sky(d_enu, 25.0, 0.0, -2.3), weights);
  }
  EXPECT_LT(troposphere_alone.fitted_error(), -2.5) << "the zenith fit takes some of the ionosphere";
  EXPECT_GT(std::abs(both_single.fitted_error() + 1.0), 0.5) << "one signature cannot tell them apart";
  EXPECT_NEAR(both_beside.fitted_error(), -1.0, 1e-9);
  EXPECT_TRUE(both_beside.mismatch());
  EXPECT_NEAR(none_beside.fitted_error(), 0.0, 1e-9);
  EXPECT_FALSE(none_beside.mismatch());
  // One satellite more is needed for the extra unknown: seven of the eight here.
  DelayMismatchDetector few(beside);
  std::vector<RangeResidual> six = ionosphere_sky(d_enu, 25.0, -1.0, -2.3);
  six.resize(6);
  for (int k = 0; k < 30; ++k) few.add(six, weights);
  EXPECT_EQ(few.fitted_error(), 0.0);
}

}  // namespace
}  // namespace deepnav::aiding
