#pragma once
// Which satellite: its system and its number within that system (GPS PRN 1-32, Galileo SVID
// 1-36), written as RINEX 3 writes it ("G05", "E11"). The receiver keys its channels,
// observations and fixes by it once more than one system is tracked.
#include <compare>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace deepnav {

enum class GnssSystem { gps, galileo };

/// The RINEX 3 system letter: 'G' or 'E'.
char system_letter(GnssSystem system);
/// "gps" or "galileo", as the command line and the scenario files spell systems.
std::string_view system_name(GnssSystem system);
/// The system named "gps" or "galileo" (case-insensitive); nullopt for anything else.
std::optional<GnssSystem> parse_system_name(std::string_view name);
/// Whether `system` is among `systems` (a scenario's, a receiver's).
bool includes_system(const std::vector<GnssSystem>& systems, GnssSystem system);
/// Whether `systems` is GPS alone (every output keeps its GPS-only form then).
bool is_gps_only(const std::vector<GnssSystem>& systems);
/// "gps", "gps,galileo": the systems as --systems reads them.
std::string systems_list(const std::vector<GnssSystem>& systems);

struct SatelliteId {
  GnssSystem system = GnssSystem::gps;
  int prn = 0;

  auto operator<=>(const SatelliteId&) const = default;
  /// "G05", "E11".
  std::string to_string() const;
};

/// "G05" / "E11" / "G 5" (RINEX 2 pads with a blank) -> the satellite; nullopt for another
/// system letter, a number outside 1-99 or anything malformed.
std::optional<SatelliteId> parse_satellite_id(std::string_view text);

}  // namespace deepnav
