#include "receiver/products/track_writers.hpp"

#include <fmt/format.h>

#include <cmath>

namespace deepnav {
namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
}

std::string kml_header(const std::string& name) {
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n"
      "<name>{}</name>\n<Placemark>\n<name>track</name>\n<LineString>\n<altitudeMode>absolute</altitudeMode>\n"
      "<coordinates>\n",
      name);
}

std::string kml_point(const PvtSolution& f) {
  return fmt::format("{:.9f},{:.9f},{:.3f}\n", f.llh.lon_rad * kRadToDeg, f.llh.lat_rad * kRadToDeg, f.llh.height_m);
}

std::string kml_footer() { return "</coordinates>\n</LineString>\n</Placemark>\n</Document>\n</kml>\n"; }

std::string gpx_header(const std::string& name) {
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<gpx version=\"1.1\" creator=\"deepnav\" "
      "xmlns=\"http://www.topografix.com/GPX/1/1\">\n<trk>\n<name>{}</name>\n<trkseg>\n",
      name);
}

std::string gpx_point(const PvtSolution& f, int leap_seconds) {
  const CalendarTime t = calendar_from_gps_time(f.t.plus_seconds(-leap_seconds));
  return fmt::format(
      "<trkpt lat=\"{:.9f}\" lon=\"{:.9f}\"><ele>{:.3f}</ele><time>{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:06.3f}Z</time>"
      "<sat>{}</sat><pdop>{:.2f}</pdop></trkpt>\n",
      f.llh.lat_rad * kRadToDeg, f.llh.lon_rad * kRadToDeg, f.llh.height_m, t.year, t.month, t.day, t.hour, t.minute,
      t.second, f.used_satellites.size(), f.dops.pdop);
}

std::string gpx_footer() { return "</trkseg>\n</trk>\n</gpx>\n"; }

std::string kml_track(const std::vector<PvtSolution>& fixes, const std::string& name) {
  std::string out = kml_header(name);
  for (const auto& f : fixes) out += kml_point(f);
  return out + kml_footer();
}

std::string gpx_track(const std::vector<PvtSolution>& fixes, const std::string& name, int leap_seconds) {
  std::string out = gpx_header(name);
  for (const auto& f : fixes) out += gpx_point(f, leap_seconds);
  return out + gpx_footer();
}

}  // namespace deepnav
