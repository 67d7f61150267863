#include "aiding/galileo_clock_offset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace deepnav::aiding {
namespace {

PvtSolution mixed_fix(double offset_m) {
  PvtSolution p;
  p.valid = true;
  p.system_offset_m = offset_m;
  return p;
}

TEST(GalileoClockOffset, UnknownUntilEnoughMixedFixesThenTheirMean) {
  GalileoClockOffset g;
  PvtSolution gps_only;
  gps_only.valid = true;
  for (int k = 0; k < 20; ++k) g.add(k, gps_only);  // no offset in a one-system fix
  PvtSolution invalid = mixed_fix(1e6);
  invalid.valid = false;
  g.add(20.0, invalid);
  EXPECT_EQ(g.fixes(), 0);
  EXPECT_FALSE(g.offset_m());
  for (int k = 0; k < 4; ++k) g.add(21.0 + k, mixed_fix(6.0 + (k % 2 ? 0.5 : -0.5)));
  EXPECT_FALSE(g.offset_m()) << "four fixes are not yet enough";
  g.add(25.0, mixed_fix(6.0));
  ASSERT_TRUE(g.offset_m());
  EXPECT_NEAR(*g.offset_m(), 6.0, 1e-12);
}

TEST(GalileoClockOffset, SigmaShrinksWithIndependentFixesDownToItsFloor) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 2.0);
  GalileoClockOffset g;
  for (int k = 0; k < 10; ++k) g.add(k, mixed_fix(-4.0 + n(rng)));
  // Ten fixes within one correlation time count as one: the sigma is their scatter (about 2 m).
  const double early = g.sigma_m();
  EXPECT_GT(early, 1.0);
  for (int k = 10; k < 600; ++k) g.add(k, mixed_fix(-4.0 + n(rng)));
  // 600 s: 60 independent fixes, 2 / sqrt(60) = 0.26 m, below the 0.3 m floor.
  EXPECT_DOUBLE_EQ(g.sigma_m(), GalileoClockOffsetConfig{}.floor_m);
  EXPECT_NEAR(*g.offset_m(), -4.0, 0.3);
}

}  // namespace
}  // namespace deepnav::aiding
