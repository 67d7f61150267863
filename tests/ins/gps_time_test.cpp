#include "ins/gps_time.hpp"

#include <gtest/gtest.h>

namespace deepnav {
namespace {

TEST(GpsTime, KnownEpochs) {
  const GpsTime t2022 = gps_time_from_calendar({2022, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(t2022.week, 2190);
  EXPECT_DOUBLE_EQ(t2022.sow, 518400.0);

  const GpsTime epoch = gps_time_from_calendar({1980, 1, 6, 0, 0, 0.0});
  EXPECT_EQ(epoch.week, 0);
  EXPECT_DOUBLE_EQ(epoch.sow, 0.0);

  // The two 10-bit week-number rollovers.
  const GpsTime r1 = gps_time_from_calendar({1999, 8, 22, 0, 0, 0.0});
  EXPECT_EQ(r1.week, 1024);
  EXPECT_DOUBLE_EQ(r1.sow, 0.0);
  const GpsTime r2 = gps_time_from_calendar({2019, 4, 7, 0, 0, 0.0});
  EXPECT_EQ(r2.week, 2048);
  EXPECT_DOUBLE_EQ(r2.sow, 0.0);

  const GpsTime before = gps_time_from_calendar({2019, 4, 6, 23, 59, 59.5});
  EXPECT_EQ(before.week, 2047);
  EXPECT_DOUBLE_EQ(before.sow, 604799.5);
}

TEST(GpsTime, CalendarRoundTrips) {
  const CalendarTime cases[] = {{1980, 1, 6, 0, 0, 0.0},     {1999, 8, 21, 23, 59, 59.25}, {1999, 8, 22, 0, 0, 0.0},
                                {2000, 2, 29, 12, 30, 15.5}, {2019, 4, 6, 23, 59, 59.75},  {2019, 4, 7, 0, 0, 0.125},
                                {2024, 12, 31, 23, 0, 1.0},  {2038, 1, 19, 3, 14, 7.0}};
  for (const auto& c : cases) {
    const CalendarTime back = calendar_from_gps_time(gps_time_from_calendar(c));
    EXPECT_EQ(back.year, c.year);
    EXPECT_EQ(back.month, c.month);
    EXPECT_EQ(back.day, c.day);
    EXPECT_EQ(back.hour, c.hour);
    EXPECT_EQ(back.minute, c.minute);
    EXPECT_NEAR(back.second, c.second, 1e-9);
  }
}

TEST(GpsTime, PlusSecondsCarriesWeeks) {
  const GpsTime t = GpsTime{2047, 604799.0}.plus_seconds(2.5);
  EXPECT_EQ(t.week, 2048);
  EXPECT_NEAR(t.sow, 1.5, 1e-9);
  const GpsTime back = t.plus_seconds(-2.5);
  EXPECT_EQ(back.week, 2047);
  EXPECT_NEAR(back.sow, 604799.0, 1e-9);
  EXPECT_NEAR(t.seconds_since(GpsTime{2047, 604799.0}), 2.5, 1e-9);
  const GpsTime n = GpsTime::normalized(10, -1.0);
  EXPECT_EQ(n.week, 9);
  EXPECT_DOUBLE_EQ(n.sow, 604799.0);
}

TEST(GpsTime, SecondsOfWeekDifferenceAcrossTheWeekBoundary) {
  EXPECT_DOUBLE_EQ(seconds_of_week_difference(10.0, 604790.0), 20.0);
  EXPECT_DOUBLE_EQ(seconds_of_week_difference(604790.0, 10.0), -20.0);
  EXPECT_DOUBLE_EQ(seconds_of_week_difference(300000.0, 100000.0), 200000.0);
  EXPECT_DOUBLE_EQ(seconds_of_week_difference(100000.0, 300000.0), -200000.0);
}

TEST(SampleClock, TimeFromIndexWithoutAccumulation) {
  const SampleClock clock(4.092e6);
  EXPECT_DOUBLE_EQ(clock.seconds_at(4092000), 1.0);
  EXPECT_EQ(clock.sample_at_or_after(1.0), 4092000);
  EXPECT_EQ(clock.sample_at_or_after(0.5 / 4.092e6), 1);
}

}  // namespace
}  // namespace deepnav

namespace deepnav {
namespace {

TEST(GpsTime, CalendarValidity) {
  EXPECT_EQ(days_in_month(2022, 2), 28);
  EXPECT_EQ(days_in_month(2024, 2), 29);
  EXPECT_EQ(days_in_month(2000, 2), 29);
  EXPECT_EQ(days_in_month(2100, 2), 28);
  EXPECT_EQ(days_in_month(2022, 4), 30);
  EXPECT_EQ(days_in_month(2022, 13), 0);
  EXPECT_TRUE(is_valid_calendar(CalendarTime{2022, 1, 1, 2, 0, 0.0}));
  EXPECT_TRUE(is_valid_calendar(CalendarTime{2024, 2, 29, 23, 59, 59.5}));
  EXPECT_FALSE(is_valid_calendar(CalendarTime{2022, 2, 31, 0, 0, 0.0}));
  EXPECT_FALSE(is_valid_calendar(CalendarTime{2022, 2, 29, 0, 0, 0.0}));
  EXPECT_FALSE(is_valid_calendar(CalendarTime{2022, 1, 1, -3, 0, 0.0}));
  EXPECT_FALSE(is_valid_calendar(CalendarTime{2022, 1, 1, 0, 60, 0.0}));
  EXPECT_FALSE(is_valid_calendar(CalendarTime{2022, 1, 1, 0, 0, 60.0}));
  EXPECT_FALSE(is_valid_calendar(CalendarTime{2022, 0, 1, 0, 0, 0.0}));
}

}  // namespace
}  // namespace deepnav
