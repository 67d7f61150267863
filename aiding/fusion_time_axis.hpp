#pragma once
// The recording-driven navigator's time axis (recorded_fusion.hpp): GPS seconds from the
// start of the week of the first observation epoch. The observations' receiver time tags
// and the IMU log's times (already on GPS time, see ins/imu_log_reader.hpp) are both put
// on it.
#include <string>

#include "ins/gps_time.hpp"
#include "ins/imu_file.hpp"
#include "receiver/observations/rinex_obs_reader.hpp"

namespace deepnav::aiding {

/// The fusion axis: GPS seconds from the start of the first epoch's week.
double fusion_time_s(const ObservationFile& obs, const GpsTime& t);

enum class ImuTimeBase { week_seconds, gps_seconds, unix_gps };
/// "week-seconds", "gps", "unix-gps" (throws std::invalid_argument otherwise).
ImuTimeBase parse_imu_time_base(const std::string& name);
/// Moves every IMU time from `base` onto the fusion axis of `obs`.
void to_fusion_axis(ImuLog& imu, ImuTimeBase base, const ObservationFile& obs);

}  // namespace deepnav::aiding
