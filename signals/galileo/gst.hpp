#pragma once
// Galileo System Time (Galileo OS SIS ICD 5.1.2, 5.1.8): GST week and time of week, its
// relation to GPS time, and the GPS-Galileo time offset (GGTO) the satellites broadcast.
//
// GST's start epoch is 1999-08-22 00:00:00 UTC less 13 s, which is where GPS week 1024
// begins: GST and GPS time share the second and the week boundaries, GST week = GPS week -
// 1024, and the two scales differ only by the GGTO, a few tens of nanoseconds.
#include "ins/gps_time.hpp"

namespace deepnav::galileo {

/// A time on GST: the full week number counted from GST week 0 (the I/NAV message carries its
/// 12 least significant bits) and seconds of week in [0, 604800).
struct GstTime {
  int week = 0;
  double tow_s = 0.0;

  /// Normalises tow_s into [0, 604800) by carrying whole weeks.
  static GstTime normalized(int week, double tow_s);
  /// this - other, in seconds.
  double seconds_since(const GstTime& other) const {
    return (week - other.week) * kSecondsPerWeek + (tow_s - other.tow_s);
  }
};

/// The same instant's label on the other scale, given GST - GPST (the GGTO; 0 where it is not
/// known, an error of tens of ns).
GpsTime gps_time_from_gst(const GstTime& t, double gst_minus_gpst_s = 0.0);
GstTime gst_from_gps_time(const GpsTime& t, double gst_minus_gpst_s = 0.0);

/// GPS to Galileo time offset parameters (I/NAV word type 10, F/NAV page 4; RINEX GAGP).
struct GgtoParameters {
  double a0g_s = 0.0;    ///< constant term
  double a1g_sps = 0.0;  ///< rate
  int t0g_s = 0;         ///< reference time, seconds of week (multiple of 3600)
  int wn0g = 0;          ///< reference week: 6 bits (modulo 64) as broadcast, or full (RINEX)
  bool valid = false;
};

/// `ggto` with WN0G as broadcast (modulo 64) made a full GST week: the one nearest `gst_week`.
GgtoParameters with_full_reference_week(GgtoParameters ggto, int gst_week);

/// GST - GPST at GST t (ICD 5.1.8): A0G + A1G (TOW - t0G + 604800 (WN - WN0G)), with the week
/// difference taken modulo 64 into [-32, 32) since WN0G is broadcast modulo 64.
double gst_minus_gpst_s(const GgtoParameters& ggto, const GstTime& t);

}  // namespace deepnav::galileo
