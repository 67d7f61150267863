// The navigation data the receiver uses before its own are decoded: an assisted ephemeris
// only once a satellite needs one and none is in use, a guided start's ephemeris never
// replacing one in use, neither reported as decoded, assisted ionosphere parameters until
// valid ones exist.
#include "receiver/navdata/broadcast_navigation.hpp"

#include <gtest/gtest.h>

namespace deepnav {
namespace {

Ephemeris ephemeris(int prn, int iode) {
  Ephemeris e;
  e.prn = prn;
  e.iode = iode;
  e.week = 2190;
  e.toe_s = 7200.0;
  return e;
}

const GpsTime kNearToe{2190, 7000.0};
const GpsTime kDayLater{2190, 7200.0 + 86400.0};

TEST(BroadcastNavigation, AssistedEphemeridesAreUsedOnlyOnceAdopted) {
  BroadcastNavigation nav;
  EXPECT_FALSE(nav.available(5, kNearToe).has_value());
  NavData assisted;
  assisted.ephemerides = {ephemeris(5, 1)};
  nav.set_assisted(assisted);
  ASSERT_TRUE(nav.available(5, kNearToe).has_value());
  EXPECT_EQ(nav.available(5, kNearToe)->iode, 1);
  EXPECT_FALSE(nav.available(5, kDayLater).has_value());  // outside its fit interval
  EXPECT_EQ(nav.ephemeris(5), nullptr);
  nav.adopt_assisted(5, kDayLater);
  EXPECT_EQ(nav.ephemeris(5), nullptr);
  nav.adopt_assisted(5, kNearToe);
  ASSERT_NE(nav.ephemeris(5), nullptr);
  EXPECT_EQ(nav.ephemeris(5)->iode, 1);
  EXPECT_EQ(nav.in_use().size(), 1u);
  EXPECT_TRUE(nav.decoded().empty());
}

TEST(BroadcastNavigation, AnAdoptedEphemerisNeverReplacesOneInUse) {
  BroadcastNavigation nav;
  nav.adopt(6, ephemeris(6, 9));
  nav.adopt(6, ephemeris(6, 10));
  EXPECT_EQ(nav.ephemeris(6)->iode, 9);
  NavData assisted;
  assisted.ephemerides = {ephemeris(6, 11)};
  nav.set_assisted(assisted);
  nav.adopt_assisted(6, kNearToe);
  EXPECT_EQ(nav.ephemeris(6)->iode, 9);
  EXPECT_EQ(nav.available(6, kNearToe)->iode, 9);
  EXPECT_TRUE(nav.decoded().empty());
}

TEST(BroadcastNavigation, AssistedIonosphereHoldsUntilValidParametersExist) {
  BroadcastNavigation nav;
  IonoParameters first;
  first.alpha[0] = 1e-8;
  first.valid = true;
  nav.set_assisted_iono(first);
  IonoParameters second = first;
  second.alpha[0] = 2e-8;
  nav.set_assisted_iono(second);
  EXPECT_EQ(nav.iono().alpha[0], 1e-8);
}

}  // namespace
}  // namespace deepnav
