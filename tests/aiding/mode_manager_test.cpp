// The mode manager's fallback chain and its return to the requested mode.
#include <gtest/gtest.h>

#include <stdexcept>

#include "aiding/mode_manager.hpp"

namespace deepnav::aiding {
namespace {

ModeInputs all_good() {
  ModeInputs in;
  in.ins_ready = true;
  in.filter_healthy = true;
  in.recent_pvt = true;
  in.ranging_satellites = 8;
  in.steerable_channels = 8;
  in.horizontal_sigma_m = 1.0;
  in.velocity_sigma_mps = 0.05;
  return in;
}

TEST(ModeManager, StartsScalarAndTakesTheRequestedModeOnceTheInsIsReady) {
  ModeManager m(NavMode::ultra);
  ModeInputs in = all_good();
  in.ins_ready = false;
  EXPECT_EQ(m.update(0.0, in), NavMode::scalar);
  EXPECT_EQ(m.update(1.0, all_good()), NavMode::ultra);
  ASSERT_EQ(m.changes().size(), 1u);
  EXPECT_EQ(m.changes()[0].from, NavMode::scalar);
}

TEST(ModeManager, FallsBackAlongTheChainAtOnceAndReturnsAfterTheHoldTime) {
  ModeManager m(NavMode::ultra);
  m.update(0.0, all_good());
  ModeInputs in = all_good();
  in.horizontal_sigma_m = 100.0;  // too uncertain to steer channels
  EXPECT_EQ(m.update(1.0, in), NavMode::tight);
  in.ranging_satellites = 0;
  EXPECT_EQ(m.update(2.0, in), NavMode::loose);
  in.recent_pvt = false;
  EXPECT_EQ(m.update(3.0, in), NavMode::coast);
  in.filter_healthy = false;
  EXPECT_EQ(m.update(4.0, in), NavMode::scalar);
  // Everything back: from scalar the requested mode is taken at once ...
  EXPECT_EQ(m.update(5.0, all_good()), NavMode::ultra);
  // ... from a fallback mode only after it has been possible for return_after_s.
  in = all_good();
  in.steerable_channels = 0;
  EXPECT_EQ(m.update(6.0, in), NavMode::tight);
  EXPECT_EQ(m.update(6.5, all_good()), NavMode::tight);
  EXPECT_EQ(m.update(7.0, all_good()), NavMode::tight);
  EXPECT_EQ(m.update(8.6, all_good()), NavMode::ultra);
  EXPECT_FALSE(m.changes().back().reason.empty());
}

TEST(ModeManager, UltraNeedsAConvergedFilterToStartButToleratesMoreToKeepGoing) {
  ModeManager m(NavMode::ultra);
  ModeInputs in = all_good();
  in.horizontal_sigma_m = 20.0;
  EXPECT_EQ(m.update(0.0, in), NavMode::tight);  // not converged enough to take over
  in.horizontal_sigma_m = 5.0;
  m.update(1.0, in);
  EXPECT_EQ(m.update(3.5, in), NavMode::ultra);
  in.horizontal_sigma_m = 20.0;  // coasting through a fade: still driving the channels
  EXPECT_EQ(m.update(4.0, in), NavMode::ultra);
}

TEST(ModeManager, ParsesTheUserModesOnly) {
  EXPECT_EQ(parse_nav_mode("loose"), NavMode::loose);
  EXPECT_EQ(parse_nav_mode("ultra"), NavMode::ultra);
  EXPECT_THROW(parse_nav_mode("coast"), std::invalid_argument);
  EXPECT_THROW(parse_nav_mode("deep"), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav::aiding
