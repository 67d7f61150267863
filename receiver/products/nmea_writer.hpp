#pragma once
// NMEA 0183 sentences of a fix: GGA, RMC, GSA and GSV, with checksums.
// Times are UTC: GPS time minus the leap seconds (from the broadcast UTC parameters
// when decoded, else the value given).
//
// Talkers: a fix of GPS satellites only is written as it always was (GP, no system ID
// fields); one of Galileo satellites only with GA; one of both with GN for GGA and RMC.
// Outside the GPS-only case GSA follows NMEA 4.1: one sentence per system, each ending in
// its system ID (1 GPS, 3 Galileo) and listing that system's satellites (Galileo by
// SVID). GSV is per system under the system's own talker (GPGSV, GAGSV).
#include <map>
#include <string>

#include "receiver/pvt/pvt_solver.hpp"

namespace deepnav {

/// "*HH" checksum of the text between '$' and '*'.
std::string nmea_checksum(const std::string& body);
/// The four sentences (GGA, RMC, GSA, GSV...) for a valid fix, each ending in CRLF.
/// `dead_reckoning`: the solution is carried by the INS (an aided mode coasting), written as
/// GGA quality 6 and RMC mode indicator E (estimated), not as a GNSS fix.
/// `cn0_dbhz`: the C/N0 of the satellites, for GSV.
std::string nmea_sentences(const PvtSolution& fix, const std::map<SatelliteId, double>& cn0_dbhz, int leap_seconds,
                           bool dead_reckoning = false);

}  // namespace deepnav
