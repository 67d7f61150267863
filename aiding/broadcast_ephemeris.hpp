#pragma once
// A satellite's broadcast orbit and clock as the aided modes carry it: GPS LNAV or Galileo
// I/NAV, and the system it names.
#include <variant>

#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav::aiding {

using BroadcastEphemeris = std::variant<Ephemeris, galileo::GalileoEphemeris>;

inline GnssSystem system_of(const BroadcastEphemeris& eph) {
  return std::holds_alternative<Ephemeris>(eph) ? GnssSystem::gps : GnssSystem::galileo;
}

}  // namespace deepnav::aiding
