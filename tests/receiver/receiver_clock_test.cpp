// The receiver clock: set once four transmit times and a week near the data exist, 68 ms
// after the latest transmit time, then running with the samples; steered by biases beyond
// a kilometre; the broadcast 10-bit week resolved against the reference week, the assisted
// ephemerides or the build date, and a week that contradicts the reference an error whose
// advice names the week the data is in. Near a week boundary a reference week alone does
// not date the clock: the data may lie on either side.
#include "receiver/receiver_clock.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "receiver/build_date.hpp"
#include "signals/gps_constants.hpp"
#include "tests/support/error_message.hpp"

namespace deepnav {
namespace {

constexpr double kFs = 4.0e6;
// Mid-week (Wednesday noon): far from either week boundary.
const std::vector<double> kFourTransmitTimes{302400.010, 302400.020, 302400.004, 302400.015};

using testing::error_of;

TEST(ReceiverClock, IsSetOnceFourTransmitTimesExist) {
  ReceiverClock clock(kFs, 2190, "--week");
  clock.set_from_transmit_times({302400.010, 302400.020, 302400.004}, 8000);
  EXPECT_FALSE(clock.is_set());
  EXPECT_FALSE(clock.at(8000).has_value());
  clock.set_from_transmit_times(kFourTransmitTimes, 8000);
  ASSERT_TRUE(clock.is_set());
  // The latest transmit time plus the 68 ms a signal travels, at the sample it was set at.
  const GpsTime t = *clock.at(8000);
  EXPECT_EQ(t.week, 2190);
  EXPECT_NEAR(t.sow, 302400.020 + kInitialTravelTime_s, 1e-9);
  // Then it runs with the sample count.
  EXPECT_NEAR(clock.at(8000 + 2 * static_cast<std::int64_t>(kFs))->seconds_since(t), 2.0, 1e-9);
  EXPECT_EQ(clock.reference()->reference_sample, 8000);
  // Once set, later transmit times leave it alone.
  clock.set_from_transmit_times({500.0, 500.0, 500.0, 500.0}, 9000);
  EXPECT_NEAR(clock.at(8000)->sow, t.sow, 1e-12);
}

TEST(ReceiverClock, WithoutAReferenceWaitsForTheBroadcastWeek) {
  // The build date alone resolves a broadcast week but never sets the clock: a guess could
  // put every product years off.
  ReceiverClock clock(kFs, 0, "--week");
  clock.set_from_transmit_times(kFourTransmitTimes, 8000);
  EXPECT_FALSE(clock.is_set());
  const int build_week = build_time().week;
  EXPECT_EQ(clock.resolution_week(), build_week);
  clock.take_broadcast_week(5, build_week % 1024, 302396.0, 4000);
  EXPECT_EQ(clock.signal_week(), build_week);
  clock.set_from_transmit_times(kFourTransmitTimes, 8000);
  ASSERT_TRUE(clock.is_set());
  EXPECT_EQ(clock.at(8000)->week, build_week);
}

TEST(ReceiverClock, TakesTheWeekNeighbourNearestTheSignalsWeek) {
  // Subframe 1 began just after a week boundary while the transmit times lie just before
  // it: the clock takes whichever week puts its time nearest that subframe.
  ReceiverClock clock(kFs, 2191, "--week");
  clock.take_broadcast_week(5, 2191 % 1024, 6.0, 0);
  clock.set_from_transmit_times({604799.90, 604799.95, 604799.85, 604799.88}, 8000);
  ASSERT_TRUE(clock.is_set());
  // 68 ms after the latest, week 2191 has begun: sow 0.018 of week 2191 (not of 2192, the
  // signal's week run past its end).
  const GpsTime t = *clock.at(8000);
  EXPECT_EQ(t.week, 2191);
  EXPECT_NEAR(t.sow, 604799.95 + kInitialTravelTime_s - kSecondsPerWeek, 1e-6);

  // Ten seconds before the boundary: the end of week 2190.
  ReceiverClock before(kFs, 2191, "--week");
  before.take_broadcast_week(5, 2191 % 1024, 6.0, 0);
  before.set_from_transmit_times({604790.0, 604790.0, 604790.0, 604790.0}, 8000);
  EXPECT_EQ(before.at(8000)->week, 2190);
}

TEST(ReceiverClock, SteersOnlyByBiasesBeyondAKilometre) {
  ReceiverClock clock(kFs, 2190, "--week");
  clock.steer(5000.0);  // not set yet: nothing to steer
  EXPECT_EQ(clock.steps_s(), 0.0);
  clock.set_from_transmit_times(kFourTransmitTimes, 0);
  const GpsTime set = *clock.at(0);
  clock.steer(900.0);
  EXPECT_EQ(clock.steps_s(), 0.0);
  EXPECT_EQ(clock.at(0)->sow, set.sow);
  clock.steer(3000.0);
  clock.steer(-1500.0);
  const double steps_s = -(3000.0 - 1500.0) / gps::kSpeedOfLight_mps;
  EXPECT_NEAR(clock.steps_s(), steps_s, 1e-15);
  EXPECT_NEAR(clock.at(0)->seconds_since(set), steps_s, 1e-9);
}

TEST(ReceiverClock, AssistedEphemeridesGiveTheWeekNearTheData) {
  ReceiverClock clock(kFs, 0, "--week");
  NavData nav;
  nav.source = "brdc0010.22n";
  Ephemeris e;
  e.week = 2190;
  e.toe_s = 7200.0;
  nav.ephemerides.push_back(e);
  clock.use_assisted_ephemerides(nav);
  EXPECT_EQ(clock.resolution_week(), 2190);
  clock.set_from_transmit_times(kFourTransmitTimes, 0);
  ASSERT_TRUE(clock.is_set());
  EXPECT_EQ(clock.at(0)->week, 2190);
  // The clock set from assistance must agree with the first subframe 1: five weeks off is
  // a navigation file of another day.
  const std::string error = error_of([&] { clock.take_broadcast_week(5, 2195 % 1024, 302396.0, 0); });
  EXPECT_NE(error.find("the assisted ephemerides (brdc0010.22n, week 2190)"), std::string::npos) << error;
  EXPECT_NE(error.find("a navigation file of another day?"), std::string::npos) << error;
}

TEST(ReceiverClock, ABroadcastWeekFarFromTheReferenceIsAnError) {
  ReceiverClock clock(kFs, 2190, "--week");
  // 252 modulo 1024, nearest 2190: week 2300.
  const std::string error = error_of([&] { clock.take_broadcast_week(9, 252, 96.0, 0); });
  EXPECT_NE(error.find("the GPS week of --week 2190 contradicts the signal: PRN 9 broadcasts week number 252"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("give --week 2300 or leave it out"), std::string::npos) << error;
}

TEST(ReceiverClock, AGstWeekDatesTheClockAsGpsWeekPlus1024) {
  ReceiverClock clock(kFs, 0, "--week");
  clock.set_from_transmit_times(kFourTransmitTimes, 0);
  EXPECT_FALSE(clock.is_set());  // no week known from the build date alone
  clock.take_galileo_week(3, 1166, 73800.0, 0);
  ASSERT_EQ(clock.signal_week(), 2190);
  clock.set_from_transmit_times(kFourTransmitTimes, 0);
  ASSERT_TRUE(clock.is_set());
  EXPECT_EQ(clock.at(0)->week, 2190);
  // The first week decides: a later GPS subframe 1 is not taken.
  clock.take_broadcast_week(9, 2191 % 1024, 96.0, 0);
  EXPECT_EQ(clock.signal_week(), 2190);
}

TEST(ReceiverClock, AGstWeekFarFromTheReferenceIsAnErrorNamingTheSatellite) {
  ReceiverClock clock(kFs, 2190, "--week");
  const std::string error = error_of([&] { clock.take_galileo_week(11, 1266, 96.0, 0); });
  EXPECT_NE(error.find("the GPS week of --week 2190 contradicts the signal: E11 broadcasts GST week 1266, i.e. "
                       "week 2290"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("give --week 2290 or leave it out"), std::string::npos) << error;
}

TEST(ReceiverClock, AWeekEitherSideOfTheReferenceIsNoContradiction) {
  ReceiverClock clock(kFs, 2190, "--week");
  clock.take_broadcast_week(9, 2191 % 1024, 96.0, 0);
  EXPECT_EQ(clock.signal_week(), 2191);
  // The first subframe 1 decides; later ones change nothing.
  clock.take_broadcast_week(9, 2189 % 1024, 96.0, 0);
  EXPECT_EQ(clock.signal_week(), 2191);
}

TEST(ReceiverClock, NearAWeekBoundaryAReferenceWeekWaitsForTheSignal) {
  // Transmit times 10 s into a week: with --week 2190 they could be of week 2190 (data that
  // began just after its start) or 2191 (data that began in 2190, before the boundary).
  const std::vector<double> after_boundary{10.010, 10.020, 10.004, 10.015};
  ReceiverClock clock(kFs, 2190, "--week");
  clock.set_from_transmit_times(after_boundary, 8000);
  EXPECT_FALSE(clock.is_set());
  // Subframe 1 sent at second 6 of week 2191 settles it.
  clock.take_broadcast_week(5, 2191 % 1024, 6.0, 4000);
  clock.set_from_transmit_times(after_boundary, 8000);
  ASSERT_TRUE(clock.is_set());
  EXPECT_EQ(clock.at(8000)->week, 2191);
  // Just before a boundary too; an hour away the reference week dates the clock.
  ReceiverClock before(kFs, 2191, "--week");
  before.set_from_transmit_times({604790.0, 604790.0, 604790.0, 604790.0}, 8000);
  EXPECT_FALSE(before.is_set());
  before.set_from_transmit_times({604800.0 - kWeekBoundaryMargin_s - 1.0, 0.0, 0.0, 0.0}, 8000);
  ASSERT_TRUE(before.is_set());
  EXPECT_EQ(before.at(8000)->week, 2191);
}

TEST(ReceiverClock, AssistedEphemeridesDateTheClockNearABoundary) {
  // The assisted ephemerides' epoch is a time, hours from the data: it tells the week of
  // transmit times 10 s into a week (2191), where --week 2190 alone could not.
  ReceiverClock clock(kFs, 2190, "--week");
  NavData nav;
  nav.source = "brdc0010.22n";
  Ephemeris e;
  e.week = 2190;
  e.toe_s = 597600.0;  // 2022-01-01 22:00
  nav.ephemerides.push_back(e);
  clock.use_assisted_ephemerides(nav);
  EXPECT_EQ(clock.resolution_week(), 2190);  // --week still resolves the week numbers
  clock.set_from_transmit_times({10.010, 10.020, 10.004, 10.015}, 8000);
  ASSERT_TRUE(clock.is_set());
  EXPECT_EQ(clock.at(8000)->week, 2191);
  EXPECT_NEAR(clock.at(8000)->sow, 10.020 + kInitialTravelTime_s, 1e-9);
  // The signal agrees: week 2191 sent at second 6 (the clock 4 s later by then).
  EXPECT_NO_THROW(clock.take_broadcast_week(5, 2191 % 1024, 6.0, 8000));
}

TEST(ReceiverClock, AClockAWeekOffNamesTheWeekOfTheData) {
  // --week 2191 for data of Wednesday of week 2190: the clock is dated a week late; the
  // first subframe 1 (week 2190, a week either side of 2191, so no contradiction of the
  // reference itself) shows it. The advice names the data's week, not the one given.
  ReceiverClock clock(kFs, 2191, "--week");
  clock.set_from_transmit_times(kFourTransmitTimes, 0);
  ASSERT_TRUE(clock.is_set());
  EXPECT_EQ(clock.at(0)->week, 2191);
  const std::string error = error_of([&] { clock.take_broadcast_week(9, 2190 % 1024, 302400.0, 0); });
  EXPECT_NE(error.find("the GPS week of --week 2191 contradicts the signal: PRN 9 broadcasts week number 142"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("i.e. week 2190, 7.0 days from the receiver clock it dated"), std::string::npos) << error;
  EXPECT_NE(error.find("the data is in week 2190 where the clock was set; give --week 2190 or leave it out"),
            std::string::npos)
      << error;
  EXPECT_EQ(error.find("give --week 2191"), std::string::npos) << error;
}

TEST(ReceiverClock, ANegativeReferenceWeekIsAnError) {
  EXPECT_EQ(error_of([] { ReceiverClock(kFs, -3, "--week"); }), "--week -3 is negative");
}

}  // namespace
}  // namespace deepnav
