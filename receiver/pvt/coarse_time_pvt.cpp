#include "receiver/pvt/coarse_time_pvt.hpp"

#include "receiver/pvt/range_model.hpp"

namespace deepnav {

PvtSolution pvt_solution_of(const CoarseTimeFix& fix, const std::map<int, Ephemeris>& ephemerides) {
  PvtSolution s;
  s.valid = fix.valid;
  s.reason = fix.reason;
  s.t = fix.receive_time;
  s.r_ecef_m = fix.r_ecef_m;
  s.llh = fix.llh;
  s.clock_bias_m = fix.clock_bias_m;
  s.clock_drift_mps = fix.clock_drift_mps.value_or(0.0);
  s.dops = fix.dops;
  // A coarse-time fix is of GPS satellites.
  const auto gps = [](int prn) { return SatelliteId{GnssSystem::gps, prn}; };
  for (const int prn : fix.used_prns) s.used_satellites.push_back(gps(prn));
  for (const int prn : fix.excluded_prns) s.excluded_satellites.push_back(gps(prn));
  if (fix.quality.passed) s.raim = fix.excluded_prns.empty() ? RaimStatus::passed : RaimStatus::excluded;
  s.raim_statistic = fix.quality.chi_square;
  s.raim_threshold = fix.quality.chi_square_threshold;
  for (const auto& [prn, r] : fix.residuals_m) s.residuals_m[gps(prn)] = r;
  for (const auto& [prn, el] : fix.elevation_rad) s.elevation_rad[gps(prn)] = el;
  s.iterations = fix.quality.iterations;
  // Azimuths only place the satellites in NMEA GSV: atmosphere left out.
  const AtmosphereModels none{IonosphereModel::none, TroposphereModel::none};
  for (const int prn : fix.used_prns) {
    const auto it = ephemerides.find(prn);
    if (it == ephemerides.end()) continue;
    s.azimuth_rad[gps(prn)] =
        predict_range(it->second, fix.receive_time, 0.0, fix.r_ecef_m, Eigen::Vector3d::Zero(), {}, none).azimuth_rad;
  }
  return s;
}

}  // namespace deepnav
