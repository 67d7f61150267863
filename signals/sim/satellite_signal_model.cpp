#include "signals/sim/satellite_signal_model.hpp"

#include <Eigen/Geometry>

#include "ins/frames.hpp"
#include "signals/atmosphere.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/line_of_sight.hpp"

namespace deepnav {
namespace {

/// The signal of a satellite seen along `los` whose code leaves it dts_signal_s late on the
/// receiver's time scale (clock, group delay and, for Galileo, the GST-GPST offset).
SatelliteInstant evaluate_along(const LineOfSight& los, double dts_signal_s, const SatelliteId& id,
                                const IonoParameters& iono, const ErrorWorld& world, const ReceiverInstant& rx,
                                double if_hz) {
  constexpr double c = gps::kSpeedOfLight_mps;
  SatelliteInstant s;
  const auto look = look_angles(rx.llh, rx.r_ecef_m, los.r_sat_ecef_m);
  s.elevation_rad = look.elevation_rad;
  s.azimuth_rad = look.azimuth_rad;
  s.range_m = los.range_m;
  s.range_rate_mps = los.range_rate_mps;
  s.sat_clock_m = c * dts_signal_s;
  if (world.orbit_clock().active()) {
    // The true satellite is off the broadcast one by the RAC error; to first order the
    // range changes by its projection on the line of sight (the rest is below 1e-7 m).
    const OrbitClockErrorSample e = world.orbit_clock().at(id, rx.t_true);
    const Eigen::Vector3d v_inertial_mps =
        los.v_sat_ecef_mps + Eigen::Vector3d(0.0, 0.0, gps::kEarthRate_radps).cross(los.r_sat_ecef_m);
    s.orbit_m = los.unit_rx_to_sat.dot(rac_to_ecef(los.r_sat_ecef_m, v_inertial_mps) * e.rac_m);
    s.sat_clock_error_m = e.clock_m;
  }
  if (s.elevation_rad > 0.0) {
    if (iono.valid)
      s.iono_broadcast_m =
          c * klobuchar_delay_s(iono, rx.llh.lat_rad, rx.llh.lon_rad, s.azimuth_rad, s.elevation_rad, rx.t_true.sow);
    s.tropo_model_m = troposphere_delay_m(rx.llh.lat_rad, rx.llh.height_m, s.elevation_rad);
    if (world.switches().ionosphere)
      s.iono_m = world.ionosphere().delay_m(s.iono_broadcast_m, rx.llh, s.azimuth_rad, s.elevation_rad, rx.t_true);
    if (world.switches().troposphere)
      s.tropo_m = world.troposphere().spec().model == TroposphereTruthSpec::Model::saastamoinen_standard
                      ? s.tropo_model_m
                      : world.troposphere().delay_m(rx.llh.lat_rad, rx.llh.height_m, s.elevation_rad, rx.t_true);
  }
  s.antenna_gain_db = antenna_gain_db(world.antenna(), s.elevation_rad);
  const double common_m =
      s.range_m + s.orbit_m + c * rx.clock_bias_s - (s.sat_clock_m + s.sat_clock_error_m) + s.tropo_m;
  s.pseudorange_m = common_m + s.iono_m;
  const double carrier_range_m = common_m - s.iono_m;

  // t_sv = t_rcv - P/c, counted from the reference epoch.
  s.code_chips = (rx.t_rcv_rel_s - s.pseudorange_m / c) * gps::kCodeRate_cps;
  s.carrier_cycles = if_hz * rx.t_rcv_rel_s - gps::kL1_Hz * carrier_range_m / c;
  // Rate of the carrier range: geometry plus the two clock drifts (atmosphere and broadcast
  // error rates are below a centimetre per second and are left out of this reported value
  // only: the carrier phase above carries them).
  const double carrier_range_rate_mps = s.range_rate_mps + c * (rx.clock_drift_sps - los.satellite.clock_drift_sps);
  s.doppler_hz = -gps::kL1_Hz * carrier_range_rate_mps / c;
  return s;
}

}  // namespace

SatelliteInstant evaluate_satellite(const Ephemeris& eph, const IonoParameters& iono, const ErrorWorld& world,
                                    const ReceiverInstant& rx, double if_hz) {
  const LineOfSight los = line_of_sight(eph, rx.t_true, rx.r_ecef_m, rx.v_ecef_mps);
  const double dts_l1_s = los.satellite.clock_bias_s - eph.tgd_s;
  return evaluate_along(los, dts_l1_s, SatelliteId{GnssSystem::gps, eph.prn}, iono, world, rx, if_hz);
}

SatelliteInstant evaluate_satellite(const galileo::GalileoEphemeris& eph, double gst_minus_gpst_s,
                                    const IonoParameters& iono, const ErrorWorld& world, const ReceiverInstant& rx,
                                    double if_hz) {
  const LineOfSight los = line_of_sight(eph, gst_minus_gpst_s, rx.t_true, rx.r_ecef_m, rx.v_ecef_mps);
  const galileo::GstTime t_tx = galileo::gst_from_gps_time(los.transmit_time, gst_minus_gpst_s);
  // The code leaves when the satellite's clock reads GST t_sv = t_tx + dts_E1; on the
  // receiver's GPS time scale that label is GGTO later still.
  const double dts_e1_s = galileo::e1_clock_correction_s(eph, t_tx) + gst_minus_gpst_s;
  return evaluate_along(los, dts_e1_s, SatelliteId{GnssSystem::galileo, eph.prn}, iono, world, rx, if_hz);
}

SatelliteInstant evaluate_satellite(const Ephemeris& eph, const IonoParameters& iono, AtmosphereSwitches atmosphere,
                                    const ReceiverInstant& rx, double if_hz) {
  return evaluate_satellite(eph, iono, ErrorWorld(atmosphere), rx, if_hz);
}

}  // namespace deepnav
