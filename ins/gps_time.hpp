#pragma once
// GPS time as (week, seconds of week) and the integer sample clock that is the
// master clock of every run: time since the start is derived from the sample
// index on demand, never accumulated.
#include <cstdint>

namespace deepnav {

inline constexpr double kSecondsPerWeek = 604800.0;

struct GpsTime {
  int week = 0;
  double sow = 0.0;  ///< seconds of week, kept in [0, 604800)

  /// Normalises sow into [0, 604800) by carrying whole weeks.
  static GpsTime normalized(int week, double sow);
  GpsTime plus_seconds(double dt_s) const { return normalized(week, sow + dt_s); }
  /// this - other, in seconds.
  double seconds_since(const GpsTime& other) const { return (week - other.week) * kSecondsPerWeek + (sow - other.sow); }
};

/// Calendar date and time on the GPS time scale (no leap seconds applied).
struct CalendarTime {
  int year = 1980, month = 1, day = 6, hour = 0, minute = 0;
  double second = 0.0;
};

/// Days in a month of the Gregorian calendar (month 1..12; 0 for any other month).
int days_in_month(int year, int month);
/// Whether the fields name a real instant: month 1..12, day within that month (Feb 29 in
/// leap years only), hour 0..23, minute 0..59, second in [0, 60).
bool is_valid_calendar(const CalendarTime& c);

GpsTime gps_time_from_calendar(const CalendarTime& c);
CalendarTime calendar_from_gps_time(const GpsTime& t);

/// Difference t - t_ref in seconds, folded into [-302400, 302400) as IS-GPS-200 asks
/// for tk = t - toe (handles the end/start-of-week crossover).
double seconds_of_week_difference(double t_sow, double t_ref_sow);

/// Integer sample counter -> time. fs is exact for rates that are whole numbers
/// of Hz, which all supported front ends are.
class SampleClock {
 public:
  explicit SampleClock(double sample_rate_hz) : fs_hz_(sample_rate_hz) {}
  double sample_rate_hz() const { return fs_hz_; }
  /// Seconds from sample 0 to sample n (one division, no accumulation).
  double seconds_at(std::int64_t n) const { return static_cast<double>(n) / fs_hz_; }
  /// First sample index at or after t seconds.
  std::int64_t sample_at_or_after(double t_s) const;

 private:
  double fs_hz_;
};

}  // namespace deepnav
