#pragma once
// RINEX 3.04 observation file: C1C (pseudorange, m), L1C (carrier phase, cycles, growing
// with range), D1C (Doppler, Hz), S1C (C/N0, dB-Hz) per satellite and epoch, of GPS L1 C/A
// and of Galileo E1 (RINEX 3.04 Table A2: attribute C is E1-C, the pilot the receiver
// tracks). File type G (GPS), E (Galileo) or M (mixed) after the systems the receiver
// tracks, one SYS / # / OBS TYPES record each; epochs on GPS time (TIME OF FIRST OBS
// "GPS") in every case. A satellite of a system the header does not declare is left out:
// a reader could not tell its fields.
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/gnss_receiver.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

struct RinexObsHeader {
  std::string marker = "DEEPNAV";
  std::string program = "deepnav";
  Eigen::Vector3d approx_position_ecef_m = Eigen::Vector3d::Zero();
  double interval_s = 1.0;
  std::vector<GnssSystem> systems = {GnssSystem::gps};  ///< in the order of the type records
};

/// The header; `first_observation` (the first epoch's receiver time) when there is one.
std::string rinex3_observation_header(const RinexObsHeader& header, const std::optional<GpsTime>& first_observation);
/// One epoch's record ("" for an epoch without receiver time or observations of `systems`).
std::string rinex3_observation_epoch(const ReceiverEpoch& epoch,
                                     const std::vector<GnssSystem>& systems = {GnssSystem::gps});

/// The whole file; `epochs` carry the receiver time of each epoch (those without are skipped).
/// The header's systems are those given in it.
std::string rinex3_observation_file(const RinexObsHeader& header, const std::vector<ReceiverEpoch>& epochs);

}  // namespace deepnav
