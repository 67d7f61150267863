#include "receiver/products/rinex_obs_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
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

/// RINEX VERSION / TYPE's satellite system field: one letter and its name.
std::string file_system(const std::vector<GnssSystem>& systems) {
  if (systems.size() > 1) return "M (MIXED)";
  return systems.empty() || systems[0] == GnssSystem::gps ? "G (GPS)" : "E (GALILEO)";
}

bool declared(const std::vector<GnssSystem>& systems, GnssSystem system) {
  return std::find(systems.begin(), systems.end(), system) != systems.end();
}

}  // namespace

std::string rinex3_observation_header(const RinexObsHeader& h, const std::optional<GpsTime>& first_observation) {
  std::string out;
  out += header_line(fmt::format("{:9.2f}{:11}{:<20}{:<20}", 3.04, "", "OBSERVATION DATA", file_system(h.systems)),
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
  for (const GnssSystem system : h.systems)
    out += header_line(fmt::format("{}    4 C1C L1C D1C S1C", system_letter(system)), "SYS / # / OBS TYPES");
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

std::string rinex3_observation_epoch(const ReceiverEpoch& e, const std::vector<GnssSystem>& systems) {
  const auto written = std::count_if(e.observations.begin(), e.observations.end(),
                                     [&](const ChannelObservation& o) { return declared(systems, o.system); });
  if (!e.t_rx || written == 0) return "";
  const CalendarTime c = calendar_from_gps_time(*e.t_rx);
  std::string out = fmt::format("> {:04d} {:02d} {:02d} {:02d} {:02d}{:11.7f}  0{:3d}\n", c.year, c.month, c.day,
                                c.hour, c.minute, c.second, written);
  for (const auto& o : e.observations) {
    if (!declared(systems, o.system)) continue;
    // RINEX phase grows with range: the negative of the accumulated Doppler.
    out += fmt::format("{}{:02d}{}{}{}{}\n", system_letter(o.system), o.prn, obs_field(o.pseudorange_m, true),
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
  for (const auto& e : epochs) out += rinex3_observation_epoch(e, h.systems);
  return out;
}

}  // namespace deepnav
