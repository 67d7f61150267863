#include "signals/galileo/gst.hpp"

#include <cmath>

#include "signals/galileo/galileo_constants.hpp"

namespace deepnav::galileo {

GstTime GstTime::normalized(int week, double tow_s) {
  const GpsTime t = GpsTime::normalized(week, tow_s);  // the same carry on the same week length
  return {t.week, t.sow};
}

GpsTime gps_time_from_gst(const GstTime& t, double gst_minus_gpst_s) {
  return GpsTime::normalized(t.week + kGstWeekOffsetFromGps, t.tow_s - gst_minus_gpst_s);
}

GstTime gst_from_gps_time(const GpsTime& t, double gst_minus_gpst_s) {
  return GstTime::normalized(t.week - kGstWeekOffsetFromGps, t.sow + gst_minus_gpst_s);
}

GgtoParameters with_full_reference_week(GgtoParameters ggto, int gst_week) {
  int weeks = (gst_week - ggto.wn0g) % 64;  // in (-64, 64)
  if (weeks < -32) weeks += 64;
  if (weeks >= 32) weeks -= 64;
  ggto.wn0g = gst_week - weeks;
  return ggto;
}

double gst_minus_gpst_s(const GgtoParameters& ggto, const GstTime& t) {
  int weeks = (t.week - ggto.wn0g) % 64;
  if (weeks < 0) weeks += 64;
  if (weeks >= 32) weeks -= 64;
  return ggto.a0g_s + ggto.a1g_sps * (t.tow_s - ggto.t0g_s + kSecondsPerWeek * weeks);
}

}  // namespace deepnav::galileo
