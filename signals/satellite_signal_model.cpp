#include "signals/satellite_signal_model.hpp"

#include "ins/frames.hpp"
#include "signals/atmosphere.hpp"
#include "signals/gps_constants.hpp"
#include "signals/line_of_sight.hpp"

namespace deepnav {

SatelliteInstant evaluate_satellite(const Ephemeris& eph, const IonoParameters& iono, AtmosphereSwitches atmosphere,
                                    const ReceiverInstant& rx, double if_hz) {
  constexpr double c = gps::kSpeedOfLight_mps;
  const LineOfSight los = line_of_sight(eph, rx.t_true, rx.r_ecef_m, rx.v_ecef_mps);

  SatelliteInstant s;
  const auto look = look_angles(rx.llh, rx.r_ecef_m, los.r_sat_ecef_m);
  s.elevation_rad = look.elevation_rad;
  s.azimuth_rad = look.azimuth_rad;
  s.range_m = los.range_m;
  s.range_rate_mps = los.range_rate_mps;
  const double dts_l1_s = los.satellite.clock_bias_s - eph.tgd_s;
  s.sat_clock_m = c * dts_l1_s;
  if (atmosphere.ionosphere && iono.valid && s.elevation_rad > 0.0) {
    s.iono_m = c * klobuchar_delay_s(iono, rx.llh.lat_rad, rx.llh.lon_rad, s.azimuth_rad, s.elevation_rad, rx.t_true.sow);
  }
  if (atmosphere.troposphere && s.elevation_rad > 0.0) {
    s.tropo_m = troposphere_delay_m(rx.llh.lat_rad, rx.llh.height_m, s.elevation_rad);
  }
  const double common_m = s.range_m + c * rx.clock_bias_s - s.sat_clock_m + s.tropo_m;
  s.pseudorange_m = common_m + s.iono_m;
  const double carrier_range_m = common_m - s.iono_m;

  // t_sv = t_rcv - P/c, counted from the reference epoch.
  s.code_chips = (rx.t_rcv_rel_s - s.pseudorange_m / c) * gps::kCodeRate_cps;
  s.carrier_cycles = if_hz * rx.t_rcv_rel_s - gps::kL1_Hz * carrier_range_m / c;
  // Rate of the carrier range: geometry plus the two clock drifts (atmosphere rates are
  // below a centimetre per second and are left out of this reported value only).
  const double carrier_range_rate_mps = s.range_rate_mps + c * (rx.clock_drift_sps - los.satellite.clock_drift_sps);
  s.doppler_hz = -gps::kL1_Hz * carrier_range_rate_mps / c;
  return s;
}

}  // namespace deepnav
