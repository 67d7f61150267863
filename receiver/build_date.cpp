#include "receiver/build_date.hpp"

#include <cstring>

namespace deepnav {

GpsTime build_time() {
  // __DATE__ is "Mmm dd yyyy" (the day space-padded).
  static constexpr const char* kMonths = "JanFebMarAprMayJunJulAugSepOctNovDec";
  const char* date = __DATE__;
  CalendarTime c;
  for (int m = 0; m < 12; ++m)
    if (std::strncmp(kMonths + 3 * m, date, 3) == 0) c.month = m + 1;
  c.day = (date[4] == ' ' ? 0 : date[4] - '0') * 10 + (date[5] - '0');
  c.year = (date[7] - '0') * 1000 + (date[8] - '0') * 100 + (date[9] - '0') * 10 + (date[10] - '0');
  c.hour = 12;
  return gps_time_from_calendar(c);
}

}  // namespace deepnav
