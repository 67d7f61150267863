#include "receiver/range_model.hpp"

#include <cmath>

#include "ins/frames.hpp"
#include "ins/wgs84.hpp"
#include "signals/atmosphere.hpp"

namespace deepnav {

RangePrediction predict_range(const Ephemeris& eph, const GpsTime& t_rx, double clock_bias_m,
                              const Eigen::Vector3d& r_rx_ecef_m, const IonoParameters& iono, bool troposphere) {
  constexpr double c = wgs84::kSpeedOfLight_mps;
  RangePrediction p;
  // True receive time, then two fixed-point passes on the flight time (converges to
  // well below a millimetre: the range changes by < 1 km over the correction).
  const GpsTime t_true = t_rx.plus_seconds(-clock_bias_m / c);
  double tau = 0.075;
  for (int pass = 0; pass < 3; ++pass) {
    const GpsTime t_tx = t_true.plus_seconds(-tau);
    const double dts = l1_clock_correction_s(eph, t_tx);
    const SatelliteState s = satellite_state(eph, t_tx);
    p.r_sat_ecef_m = earth_rotation_corrected(s.r_ecef_m, tau);
    p.v_sat_ecef_mps = earth_rotation_corrected(s.v_ecef_mps, tau);
    p.satellite_clock_m = c * dts;
    p.satellite_drift_mps = c * s.clock_drift_sps;
    const Eigen::Vector3d d = p.r_sat_ecef_m - r_rx_ecef_m;
    p.geometric_range_m = d.norm();
    p.los_ecef = d / p.geometric_range_m;
    tau = p.geometric_range_m / c;
  }
  const wgs84::Llh llh = wgs84::ecef_to_llh(r_rx_ecef_m);
  const LookAngles la = look_angles(llh, r_rx_ecef_m, p.r_sat_ecef_m);
  p.elevation_rad = la.elevation_rad;
  p.azimuth_rad = la.azimuth_rad;
  if (iono.valid)
    p.atmosphere_m += c * klobuchar_delay_s(iono, llh.lat_rad, llh.lon_rad, la.azimuth_rad, la.elevation_rad, t_rx.sow);
  if (troposphere && la.elevation_rad > 0.0) p.atmosphere_m += troposphere_delay_m(llh.lat_rad, llh.height_m, la.elevation_rad);
  return p;
}

}  // namespace deepnav
