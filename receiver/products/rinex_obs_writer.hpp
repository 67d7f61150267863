#pragma once
// RINEX 3.04 GPS observation file: C1C (pseudorange, m), L1C (carrier phase, cycles,
// growing with range), D1C (Doppler, Hz), S1C (C/N0, dB-Hz) per epoch.
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/gnss_receiver.hpp"

namespace deepnav {

struct RinexObsHeader {
  std::string marker = "DEEPNAV";
  std::string program = "deepnav";
  Eigen::Vector3d approx_position_ecef_m = Eigen::Vector3d::Zero();
  double interval_s = 1.0;
};

/// The header; `first_observation` (the first epoch's receiver time) when there is one.
std::string rinex3_observation_header(const RinexObsHeader& header, const std::optional<GpsTime>& first_observation);
/// One epoch's record ("" for an epoch without receiver time or observations).
std::string rinex3_observation_epoch(const ReceiverEpoch& epoch);

/// The whole file; `epochs` carry the receiver time of each epoch (those without are skipped).
std::string rinex3_observation_file(const RinexObsHeader& header, const std::vector<ReceiverEpoch>& epochs);

}  // namespace deepnav
