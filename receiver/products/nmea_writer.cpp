#include "receiver/products/nmea_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ins/frames.hpp"

namespace deepnav {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

std::string sentence(const std::string& body) { return "$" + body + nmea_checksum(body) + "\r\n"; }

/// ddmm.mmmmm / dddmm.mmmmm with hemisphere letter.
std::string angle(double deg, int degree_digits, char pos, char neg) {
  const char hemi = deg >= 0 ? pos : neg;
  deg = std::abs(deg);
  int d = static_cast<int>(deg);
  double m = (deg - d) * 60.0;
  if (m >= 59.9999995) {  // rounding would print 60.00000
    m = 0.0;
    ++d;
  }
  return fmt::format("{:0{}d}{:08.5f},{}", d, degree_digits, m, hemi);
}

/// NMEA 4.1 GNSS system ID (GSA's last field).
int nmea_system_id(GnssSystem system) { return system == GnssSystem::gps ? 1 : 3; }

/// GSV sentences of the satellites of `system` the fix uses, four per sentence, under the
/// system's own talker.
std::string satellites_in_view(const PvtSolution& fix, GnssSystem system,
                               const std::map<SatelliteId, double>& cn0_dbhz) {
  std::vector<SatelliteId> sats;
  for (const SatelliteId& s : fix.used_satellites)
    if (s.system == system) sats.push_back(s);
  const std::string talker = system == GnssSystem::gps ? "GP" : "GA";
  const int n = static_cast<int>(sats.size());
  const int messages = std::max(1, (n + 3) / 4);
  std::string out;
  for (int m = 0; m < messages; ++m) {
    std::string body = fmt::format("{}GSV,{},{},{:02d}", talker, messages, m + 1, n);
    for (int i = 4 * m; i < std::min(n, 4 * m + 4); ++i) {
      const SatelliteId sat = sats[static_cast<std::size_t>(i)];
      const double el = fix.elevation_rad.count(sat) ? fix.elevation_rad.at(sat) * kRadToDeg : 0.0;
      const auto it = cn0_dbhz.find(sat);
      const double az = fix.azimuth_rad.count(sat) ? fix.azimuth_rad.at(sat) * kRadToDeg : 0.0;
      body += fmt::format(",{:02d},{:02.0f},{:03.0f},{}", sat.prn, std::max(0.0, el), az,
                          it != cn0_dbhz.end() ? fmt::format("{:02.0f}", it->second) : std::string());
    }
    out += sentence(body);
  }
  return out;
}

}  // namespace

std::string nmea_checksum(const std::string& body) {
  unsigned char sum = 0;
  for (char ch : body) sum ^= static_cast<unsigned char>(ch);
  return fmt::format("*{:02X}", sum);
}

std::string nmea_sentences(const PvtSolution& fix, const std::map<SatelliteId, double>& cn0_dbhz, int leap_seconds,
                           bool dead_reckoning) {
  const CalendarTime utc = calendar_from_gps_time(fix.t.plus_seconds(-leap_seconds));
  const std::string hms =
      fmt::format("{:02d}{:02d}{:05.2f}", utc.hour, utc.minute, std::floor(utc.second * 100.0) / 100.0);
  const double lat = fix.llh.lat_rad * kRadToDeg, lon = fix.llh.lon_rad * kRadToDeg;
  const std::string pos = angle(lat, 2, 'N', 'S') + "," + angle(lon, 3, 'E', 'W');
  const bool gps = fix.used_count(GnssSystem::gps) > 0, galileo = fix.used_count(GnssSystem::galileo) > 0;
  const std::string talker = galileo ? (gps ? "GN" : "GA") : "GP";
  std::string out;
  // GGA quality 1: GNSS fix, 6: estimated (dead reckoning); RMC mode indicator A / E.
  out += sentence(fmt::format("{}GGA,{},{},{},{:02d},{:.1f},{:.2f},M,0.0,M,,", talker, hms, pos, dead_reckoning ? 6 : 1,
                              fix.used_satellites.size(), fix.dops.hdop, fix.llh.height_m));
  const Eigen::Vector3d v = C_e_n(fix.llh.lat_rad, fix.llh.lon_rad) * fix.v_ecef_mps;
  const double speed_knots = v.head<2>().norm() * 3600.0 / 1852.0;
  double course = std::atan2(v.y(), v.x()) * kRadToDeg;
  if (course < 0) course += 360.0;
  out += sentence(fmt::format("{}RMC,{},A,{},{:.2f},{:.1f},{:02d}{:02d}{:02d},,,{}", talker, hms, pos, speed_knots,
                              course, utc.day, utc.month, utc.year % 100, dead_reckoning ? 'E' : 'A'));
  // GPS-only: the one GPGSA without a system ID, as before; else one GSA per system used.
  const std::vector<GnssSystem> systems =
      galileo ? (gps ? std::vector{GnssSystem::gps, GnssSystem::galileo} : std::vector{GnssSystem::galileo})
              : std::vector{GnssSystem::gps};
  for (const GnssSystem system : systems) {
    std::vector<int> prns;
    for (const SatelliteId& s : fix.used_satellites)
      if (s.system == system) prns.push_back(s.prn);
    std::string list;
    for (int i = 0; i < 12; ++i)
      list += (i < static_cast<int>(prns.size()) ? fmt::format("{:02d}", prns[static_cast<std::size_t>(i)]) : "") + ",";
    const std::string system_id = talker == "GP" ? "" : fmt::format(",{}", nmea_system_id(system));
    out += sentence(fmt::format("{}GSA,A,3,{}{:.1f},{:.1f},{:.1f}{}", talker, list, fix.dops.pdop, fix.dops.hdop,
                                fix.dops.vdop, system_id));
  }
  for (const GnssSystem system : systems) out += satellites_in_view(fix, system, cn0_dbhz);
  return out;
}

}  // namespace deepnav
