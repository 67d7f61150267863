#include "signals/sim/troposphere_truth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "signals/atmosphere.hpp"
#include "signals/sim/error_presets.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const GpsTime kStart{2190, 518400.0 + 7200.0};  // 2022-01-01 02:00 GPS: day of year 1
constexpr double kSeoulLat = 37.5665 * kDeg;
constexpr double kSeoulHeight_m = 40.0;

TroposphereTruth open_sky(std::uint64_t seed, double duration_s = 3600.0) {
  return TroposphereTruth(error_preset("open-sky").troposphere, seed, kStart, duration_s);
}

TEST(NiellMapping, UnityAtZenithAndWithin2PercentOfTheCosecantAbove15Degrees) {
  const NiellMapping z = niell_mapping(45 * kDeg, 0.0, 28.0, 90 * kDeg);
  EXPECT_NEAR(z.hydrostatic, 1.0, 1e-12);
  EXPECT_NEAR(z.wet, 1.0, 1e-12);
  for (double el = 15; el <= 90; el += 5) {
    const NiellMapping m = niell_mapping(45 * kDeg, 0.0, 28.0, el * kDeg);
    EXPECT_NEAR(m.hydrostatic * std::sin(el * kDeg), 1.0, 0.02) << el;
    EXPECT_NEAR(m.wet * std::sin(el * kDeg), 1.0, 0.02) << el;
  }
  // Low elevations: Niell's published values at 45 deg N (about 5.55 hydrostatic and 5.62
  // wet at 10 deg; 10.2 and 10.8 at 5 deg), the wet function steeper than the hydrostatic.
  const NiellMapping m10 = niell_mapping(45 * kDeg, 0.0, 28.0, 10 * kDeg);
  EXPECT_NEAR(m10.hydrostatic, 5.55, 0.05);
  EXPECT_NEAR(m10.wet, 5.62, 0.05);
  const NiellMapping m5 = niell_mapping(45 * kDeg, 0.0, 28.0, 5 * kDeg);
  EXPECT_NEAR(m5.hydrostatic, 10.2, 0.15);
  EXPECT_NEAR(m5.wet, 10.8, 0.2);
  EXPECT_GT(m5.wet, m5.hydrostatic);
  // Differs from the receiver's Black & Eisner mapping by a few percent at 5 deg.
  EXPECT_GT(std::abs(m5.hydrostatic - troposphere_mapping(5 * kDeg)), 0.05);
}

TEST(NiellMapping, SeasonAndHeightTerms) {
  // Hydrostatic coefficients peak on day 28 in the north and half a year later in the south.
  const double winter_n = niell_mapping(60 * kDeg, 0.0, 28.0, 5 * kDeg).hydrostatic;
  const double summer_n = niell_mapping(60 * kDeg, 0.0, 28.0 + 182.625, 5 * kDeg).hydrostatic;
  EXPECT_NE(winter_n, summer_n);
  EXPECT_NEAR(niell_mapping(-60 * kDeg, 0.0, 28.0 + 182.625, 5 * kDeg).hydrostatic, winter_n, 1e-12);
  // Higher sites map the hydrostatic delay a little more (Niell's height correction).
  EXPECT_GT(niell_mapping(45 * kDeg, 2000.0, 100.0, 5 * kDeg).hydrostatic,
            niell_mapping(45 * kDeg, 0.0, 100.0, 5 * kDeg).hydrostatic);
  // Latitude interpolation is continuous across the table rows.
  EXPECT_NEAR(niell_mapping(44.999 * kDeg, 0.0, 100.0, 5 * kDeg).wet,
              niell_mapping(45.001 * kDeg, 0.0, 100.0, 5 * kDeg).wet, 1e-4);
}

TEST(TroposphereTruth, StandardModelIsTheReceiversModel) {
  const TroposphereTruth t(TroposphereTruthSpec{}, 1, kStart, 60.0);
  for (double el : {3.0, 10.0, 45.0, 90.0})
    EXPECT_EQ(t.delay_m(kSeoulLat, kSeoulHeight_m, el * kDeg, kStart),
              troposphere_delay_m(kSeoulLat, kSeoulHeight_m, el * kDeg));
}

TEST(TroposphereTruth, OpenSkyDiffersFromTheReceiverModelByCentimetresToDecimetres) {
  const TroposphereTruth t = open_sky(1);
  const TroposphereZenithDelay model = saastamoinen_zenith_delay(kSeoulLat, kSeoulHeight_m);
  EXPECT_NEAR(t.zenith_hydrostatic_m(kSeoulLat, kSeoulHeight_m), model.hydrostatic_m, 0.01);
  EXPECT_NEAR(t.zenith_wet_m(kSeoulHeight_m, kStart), 0.18, 0.02);  // UNB3 mid-latitude summer
  const double zenith = t.delay_m(kSeoulLat, kSeoulHeight_m, 90 * kDeg, kStart) -
                        troposphere_delay_m(kSeoulLat, kSeoulHeight_m, 90 * kDeg);
  const double low = t.delay_m(kSeoulLat, kSeoulHeight_m, 10 * kDeg, kStart) -
                     troposphere_delay_m(kSeoulLat, kSeoulHeight_m, 10 * kDeg);
  std::printf("open-sky troposphere truth - receiver model at Seoul: zenith %.3f m, 10 deg %.3f m\n", zenith, low);
  EXPECT_GT(zenith, 0.03);
  EXPECT_LT(zenith, 0.15);
  EXPECT_GT(low, 0.2);
  EXPECT_LT(low, 1.0);
  // Black & Eisner instead of Niell: the same zenith delay.
  TroposphereTruthSpec be = error_preset("open-sky").troposphere;
  be.mapping = TroposphereTruthSpec::Mapping::black_eisner;
  const TroposphereTruth tb(be, 1, kStart, 3600.0);
  EXPECT_NEAR(tb.delay_m(kSeoulLat, kSeoulHeight_m, 90 * kDeg, kStart),
              t.delay_m(kSeoulLat, kSeoulHeight_m, 90 * kDeg, kStart), 0.002);
  // Dry, cold air at altitude: far less delay than at the ground.
  EXPECT_LT(t.delay_m(kSeoulLat, 10000.0, 90 * kDeg, kStart), 0.7);
  EXPECT_LT(t.delay_m(kSeoulLat, 15000.0, 90 * kDeg, kStart), 0.4);
}

TEST(TroposphereTruth, WetRandomWalkHasTheConfiguredSizeAndIsSeeded) {
  const TroposphereTruth a = open_sky(5), b = open_sky(5), c = open_sky(6);
  EXPECT_EQ(a.wet_walk_m(kStart), 0.0);
  double diff = 0.0;
  for (int s = 0; s <= 3600; s += 7) {
    const GpsTime t = kStart.plus_seconds(s);
    EXPECT_EQ(a.wet_walk_m(t), b.wet_walk_m(t));
    diff += std::abs(a.wet_walk_m(t) - c.wet_walk_m(t));
  }
  EXPECT_GT(diff, 0.0);
  // Over many seeds, the walk after an hour has an RMS of 1.5 cm.
  double sum2 = 0.0;
  constexpr int kSeeds = 400;
  for (int seed = 0; seed < kSeeds; ++seed) sum2 += std::pow(open_sky(seed).wet_walk_m(kStart.plus_seconds(3600.0)), 2);
  EXPECT_NEAR(std::sqrt(sum2 / kSeeds), 0.015, 0.0015);
  // Continuous in time (linear between 10 s nodes): no jump between milliseconds.
  for (int ms = 0; ms < 30000; ms += 1)
    ASSERT_LT(
        std::abs(a.wet_walk_m(kStart.plus_seconds(ms * 1e-3 + 1e-3)) - a.wet_walk_m(kStart.plus_seconds(ms * 1e-3))),
        1e-5);
}

TEST(TroposphereTruth, WetDelayNeverGoesNegative) {
  TroposphereTruthSpec spec = error_preset("open-sky").troposphere;
  spec.relative_humidity = 0.02;
  spec.wet_random_walk_m_per_sqrt_h = 0.2;
  const TroposphereTruth t(spec, 3, kStart, 86400.0);
  double lowest = 1.0;
  for (int s = -60; s <= 86460; s += 10) lowest = std::min(lowest, t.zenith_wet_m(0.0, kStart.plus_seconds(s)));
  EXPECT_GE(lowest, 0.0);
  EXPECT_LT(lowest, 0.05);  // it does come down to the bound
}

}  // namespace
}  // namespace deepnav
