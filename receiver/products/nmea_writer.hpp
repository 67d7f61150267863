#pragma once
// NMEA 0183 sentences of a fix: GGA, RMC, GSA and GSV (talker GP), with checksums.
// Times are UTC: GPS time minus the leap seconds (from the broadcast UTC parameters
// when decoded, else the value given).
#include <string>

#include "receiver/pvt/pvt_solver.hpp"

namespace deepnav {

/// "*HH" checksum of the text between '$' and '*'.
std::string nmea_checksum(const std::string& body);
/// The four sentences (GGA, RMC, GSA, GSV...) for a valid fix, each ending in CRLF.
/// `dead_reckoning`: the solution is carried by the INS (an aided mode coasting), written as
/// GGA quality 6 and RMC mode indicator E (estimated), not as a GNSS fix.
std::string nmea_sentences(const PvtSolution& fix, const std::map<int, double>& cn0_dbhz, int leap_seconds,
                           bool dead_reckoning = false);

}  // namespace deepnav
