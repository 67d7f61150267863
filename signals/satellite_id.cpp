#include "signals/satellite_id.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace deepnav {

char system_letter(GnssSystem system) { return system == GnssSystem::galileo ? 'E' : 'G'; }

std::string_view system_name(GnssSystem system) { return system == GnssSystem::galileo ? "galileo" : "gps"; }

std::optional<GnssSystem> parse_system_name(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == "gps") return GnssSystem::gps;
  if (lower == "galileo") return GnssSystem::galileo;
  return std::nullopt;
}

bool includes_system(const std::vector<GnssSystem>& systems, GnssSystem system) {
  return std::find(systems.begin(), systems.end(), system) != systems.end();
}

bool is_gps_only(const std::vector<GnssSystem>& systems) { return systems == std::vector<GnssSystem>{GnssSystem::gps}; }

std::string systems_list(const std::vector<GnssSystem>& systems) {
  std::string s;
  for (GnssSystem system : systems) {
    if (!s.empty()) s += ',';
    s += system_name(system);
  }
  return s;
}

std::string SatelliteId::to_string() const { return fmt::format("{}{:02d}", system_letter(system), prn); }

std::optional<SatelliteId> parse_satellite_id(std::string_view text) {
  if (text.size() != 3) return std::nullopt;
  SatelliteId id;
  if (text[0] == 'G') {
    id.system = GnssSystem::gps;
  } else if (text[0] == 'E') {
    id.system = GnssSystem::galileo;
  } else {
    return std::nullopt;
  }
  const char tens = text[1] == ' ' ? '0' : text[1];
  if (!std::isdigit(static_cast<unsigned char>(tens)) || !std::isdigit(static_cast<unsigned char>(text[2])))
    return std::nullopt;
  id.prn = (tens - '0') * 10 + (text[2] - '0');
  if (id.prn < 1) return std::nullopt;
  return id;
}

}  // namespace deepnav
