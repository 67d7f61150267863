#include "receiver/products/rinex_obs_writer.hpp"

#include <fmt/format.h>

#include <cmath>

namespace deepnav {
namespace {

std::string header_line(const std::string& content, const char* label) {
  return fmt::format("{:<60}{:<20}\n", content.substr(0, 60), label);
}

std::string obs_field(double value, bool present) {
  if (!present || !std::isfinite(value) || std::abs(value) >= 1e10) return std::string(16, ' ');
  return fmt::format("{:14.3f}  ", value);
}

/// Sets the loss-of-lock indicator (bit 0: lock lost since the previous epoch) of a field.
std::string lli_marked(std::string field, bool lost_lock) {
  if (lost_lock && field[13] != ' ') field[14] = '1';
  return field;
}

}  // namespace

std::string rinex3_observation_header(const RinexObsHeader& h, const std::optional<GpsTime>& first_observation) {
  std::string out;
  out += header_line(fmt::format("{:9.2f}{:11}{:<20}{:<20}", 3.04, "", "OBSERVATION DATA", "G (GPS)"),
                     "RINEX VERSION / TYPE");
  out += header_line(fmt::format("{:<20}{:<20}{:<20}", h.program, "", ""), "PGM / RUN BY / DATE");
  out += header_line(h.marker, "MARKER NAME");
  out += header_line("", "OBSERVER / AGENCY");
  out += header_line(fmt::format("{:<20}{:<20}{:<20}", "", "deepnav", ""), "REC # / TYPE / VERS");
  out += header_line("", "ANT # / TYPE");
  out += header_line(fmt::format("{:14.4f}{:14.4f}{:14.4f}", h.approx_position_ecef_m.x(), h.approx_position_ecef_m.y(),
                                 h.approx_position_ecef_m.z()),
                     "APPROX POSITION XYZ");
  out += header_line(fmt::format("{:14.4f}{:14.4f}{:14.4f}", 0.0, 0.0, 0.0), "ANTENNA: DELTA H/E/N");
  out += header_line("G    4 C1C L1C D1C S1C", "SYS / # / OBS TYPES");
  out += header_line(fmt::format("{:10.3f}", h.interval_s), "INTERVAL");
  if (first_observation) {
    const CalendarTime c = calendar_from_gps_time(*first_observation);
    out += header_line(
        fmt::format("{:6d}{:6d}{:6d}{:6d}{:6d}{:13.7f}     GPS", c.year, c.month, c.day, c.hour, c.minute, c.second),
        "TIME OF FIRST OBS");
  }
  out += header_line("", "END OF HEADER");
  return out;
}

std::string rinex3_observation_epoch(const ReceiverEpoch& e) {
  if (!e.t_rx || e.observations.empty()) return "";
  const CalendarTime c = calendar_from_gps_time(*e.t_rx);
  std::string out = fmt::format("> {:04d} {:02d} {:02d} {:02d} {:02d}{:11.7f}  0{:3d}\n", c.year, c.month, c.day,
                                c.hour, c.minute, c.second, e.observations.size());
  for (const auto& o : e.observations) {
    // RINEX phase grows with range: the negative of the accumulated Doppler.
    out += fmt::format("G{:02d}{}{}{}{}\n", o.prn, obs_field(o.pseudorange_m, true),
                       lli_marked(obs_field(-o.carrier_phase_cycles, true), o.after_gap), obs_field(o.doppler_hz, true),
                       obs_field(o.cn0_dbhz, true));
  }
  return out;
}

std::string rinex3_observation_file(const RinexObsHeader& h, const std::vector<ReceiverEpoch>& epochs) {
  std::optional<GpsTime> first;
  for (const auto& e : epochs)
    if (e.t_rx) {
      first = e.t_rx;
      break;
    }
  std::string out = rinex3_observation_header(h, first);
  for (const auto& e : epochs) out += rinex3_observation_epoch(e);
  return out;
}

}  // namespace deepnav
