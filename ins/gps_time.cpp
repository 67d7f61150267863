#include "ins/gps_time.hpp"

#include <cmath>

namespace deepnav {

GpsTime GpsTime::normalized(int week, double sow) {
  const double weeks = std::floor(sow / kSecondsPerWeek);
  GpsTime t;
  t.week = week + static_cast<int>(weeks);
  t.sow = sow - weeks * kSecondsPerWeek;
  if (t.sow >= kSecondsPerWeek) {  // guard against rounding right at the boundary
    t.sow -= kSecondsPerWeek;
    ++t.week;
  }
  return t;
}

namespace {
// Days from 1970-01-01 for a proleptic Gregorian date (Howard Hinnant's algorithm).
long days_from_civil(long y, unsigned m, unsigned d) {
  y -= m <= 2;
  const long era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long>(doe) - 719468;
}

void civil_from_days(long z, int& y, int& m, int& d) {
  z += 719468;
  const long era = (z >= 0 ? z : z - 146096) / 146097;
  const unsigned doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  y = static_cast<int>(static_cast<long>(yoe) + era * 400 + (m <= 2));
}

constexpr long kGpsEpochDays = 3657;  // 1980-01-06 in days since 1970-01-01
}  // namespace

int days_in_month(int year, int month) {
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12) return 0;
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return kDays[month - 1] + (month == 2 && leap ? 1 : 0);
}

bool is_valid_calendar(const CalendarTime& c) {
  return c.month >= 1 && c.month <= 12 && c.day >= 1 && c.day <= days_in_month(c.year, c.month) && c.hour >= 0 &&
         c.hour <= 23 && c.minute >= 0 && c.minute <= 59 && c.second >= 0.0 && c.second < 60.0;
}

GpsTime gps_time_from_calendar(const CalendarTime& c) {
  const long days =
      days_from_civil(c.year, static_cast<unsigned>(c.month), static_cast<unsigned>(c.day)) - kGpsEpochDays;
  const double seconds = static_cast<double>(days % 7) * 86400.0 + c.hour * 3600.0 + c.minute * 60.0 + c.second;
  return GpsTime::normalized(static_cast<int>(days / 7), seconds);
}

CalendarTime calendar_from_gps_time(const GpsTime& t) {
  const double day_of_week = std::floor(t.sow / 86400.0);
  const long days = kGpsEpochDays + static_cast<long>(t.week) * 7 + static_cast<long>(day_of_week);
  CalendarTime c;
  civil_from_days(days, c.year, c.month, c.day);
  double sod = t.sow - day_of_week * 86400.0;
  c.hour = static_cast<int>(sod / 3600.0);
  sod -= c.hour * 3600.0;
  c.minute = static_cast<int>(sod / 60.0);
  c.second = sod - c.minute * 60.0;
  return c;
}

double seconds_of_week_difference(double t_sow, double t_ref_sow) {
  double dt = t_sow - t_ref_sow;
  if (dt > kSecondsPerWeek / 2) dt -= kSecondsPerWeek;
  if (dt < -kSecondsPerWeek / 2) dt += kSecondsPerWeek;
  return dt;
}

std::int64_t SampleClock::sample_at_or_after(double t_s) const {
  return static_cast<std::int64_t>(std::ceil(t_s * fs_hz_ - 1e-9));
}

}  // namespace deepnav
