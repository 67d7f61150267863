#include "ins/iso_date_time.hpp"

#include <gtest/gtest.h>

namespace deepnav {
namespace {

TEST(IsoDateTime, ReadsTheFieldsAndTheZ) {
  const auto t = parse_iso_date_time("2022-01-01T02:00:03.25Z", true);
  ASSERT_TRUE(t.has_value());
  EXPECT_TRUE(t->utc);
  EXPECT_EQ(t->calendar.year, 2022);
  EXPECT_EQ(t->calendar.month, 1);
  EXPECT_EQ(t->calendar.day, 1);
  EXPECT_EQ(t->calendar.hour, 2);
  EXPECT_EQ(t->calendar.minute, 0);
  EXPECT_DOUBLE_EQ(t->calendar.second, 3.25);
  const auto space = parse_iso_date_time("2021-12-02 08:47:00", false);
  ASSERT_TRUE(space.has_value());
  EXPECT_FALSE(space->utc);
  EXPECT_EQ(space->calendar.hour, 8);
}

TEST(IsoDateTime, OtherFormsAreNone) {
  for (const char* text : {"2022-01-01", "2022-1-01T00:00:00", "+2022-01-01T00:00:00", "2022-01-01T00:00:00 ",
                           "2022-01-01T00:00", "2022-01-01T00:00:00+09:00", ""})
    EXPECT_FALSE(parse_iso_date_time(text, true).has_value()) << text;
  // A "Z" only where it is allowed.
  EXPECT_FALSE(parse_iso_date_time("2022-01-01T00:00:00Z", false).has_value());
  // Fields out of range are the caller's to check (is_valid_calendar).
  EXPECT_TRUE(parse_iso_date_time("2022-13-01T25:00:00", false).has_value());
}

}  // namespace
}  // namespace deepnav
