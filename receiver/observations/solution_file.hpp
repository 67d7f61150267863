#pragma once
// RTKLIB solution files (.pos, as rnx2rtkp and rtkpost write them) as a reference or a
// baseline, and the error statistics of a solution against one.
//
// Read: time as "yyyy/mm/dd hh:mm:ss.sss" (GPST) or "week seconds-of-week", then latitude
// (deg), longitude (deg), ellipsoidal height (m), Q, ns; further columns are ignored.
// '%' lines are comments. Errors name the file, the line and the field.
//
// Statistics: every solution epoch within 10 ms of a reference epoch is compared in the
// reference's local east-north-up frame. A reference whose base was not surveyed is off
// by a constant, so next to the plain RMS the statistics give the mean offset and the
// scatter about it (RMS and maximum of the error minus the mean offset).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {

struct SolutionPoint {
  GpsTime t;
  wgs84::Llh llh{};
  int quality = 0;  ///< RTKLIB Q: 1 fix, 2 float, 5 single (0: not given)
  int satellites = 0;
};

std::vector<SolutionPoint> read_rtklib_pos(const std::string& path);

struct ReferenceErrors {
  int epochs = 0;  ///< solution epochs matched to the reference
  Eigen::Vector3d mean_offset_enu_m = Eigen::Vector3d::Zero();
  double rms_horizontal_m = 0, rms_vertical_m = 0, rms_3d_m = 0;
  /// About the mean offset.
  double scatter_rms_horizontal_m = 0, scatter_rms_vertical_m = 0, scatter_p95_horizontal_m = 0;
  double scatter_max_horizontal_m = 0, scatter_max_3d_m = 0;
  std::vector<GpsTime> matched;  ///< the epochs compared
  /// The statistics (null where no epoch was scored: there is nothing to state).
  nlohmann::json json() const;
};

/// Errors of `solution` against `reference` (time-matched within 10 ms).
ReferenceErrors reference_errors(const std::vector<SolutionPoint>& solution,
                                 const std::vector<SolutionPoint>& reference);

}  // namespace deepnav
