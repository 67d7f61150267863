#include "signals/sim/antenna_pattern.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(AntennaPattern, IsotropicIsZeroEverywhere) {
  const AntennaSpec iso{};
  for (double el = -5; el <= 90; el += 5) EXPECT_EQ(antenna_gain_db(iso, el * kDeg), 0.0);
}

TEST(AntennaPattern, PatchGoesThroughItsThreePointsAndFallsMonotonically) {
  AntennaSpec patch;
  patch.pattern = AntennaSpec::Pattern::patch;
  EXPECT_NEAR(antenna_gain_db(patch, 90 * kDeg), 0.0, 1e-12);
  EXPECT_NEAR(antenna_gain_db(patch, 10 * kDeg), -5.0, 1e-9);
  EXPECT_NEAR(antenna_gain_db(patch, 0.0), -10.0, 1e-12);
  EXPECT_NEAR(antenna_gain_db(patch, -3 * kDeg), -10.0, 1e-12);
  EXPECT_NEAR(antenna_gain_db(patch, 20 * kDeg), -2.2, 0.1);
  EXPECT_NEAR(antenna_gain_db(patch, 30 * kDeg), -0.8, 0.1);
  double previous = -100.0;
  for (double el = 0; el <= 90; el += 0.5) {
    const double g = antenna_gain_db(patch, el * kDeg);
    EXPECT_GT(g, previous) << el;
    previous = g;
  }
  patch.gain_10deg_db = -7.0;
  patch.gain_horizon_db = -15.0;
  EXPECT_NEAR(antenna_gain_db(patch, 10 * kDeg), -7.0, 1e-9);
  EXPECT_NEAR(antenna_gain_db(patch, 0.0), -15.0, 1e-12);
}

}  // namespace
}  // namespace deepnav
