#pragma once
// What one satellite's L1 C/A signal looks like at the receiver antenna at one
// instant of the receiver clock: code phase, carrier phase, Doppler, power and the
// geometry behind them. The synthesizer evaluates it at every millisecond boundary
// and interpolates linearly in between; the per-satellite truth file prints it.
//
// Timing model (all times GPS time unless named otherwise):
//   receiver clock reading  t_rcv = t_true + b            (b: receiver clock bias)
//   satellite L1 timing     t_sv  = t_tx + dts_L1         (dts_L1 = dts - TGD, IS-GPS-200 20.3.3.3.3.2)
//   code pseudorange        P_code = rho + dR + c (b - dts_L1) - dC + I + T
//   carrier pseudorange     P_carr = rho + dR + c (b - dts_L1) - dC - I + T   (ionospheric advance)
// (Galileo: t_sv is the GST the satellite clock reads, dts_E1 its clock less BGD(E1,E5b) and
// the GGTO added, so P_code holds c (b - dts_E1 - GGTO).)
// where rho is the geometric range from the light-time equation with Sagnac to the
// broadcast orbit, dR the broadcast orbit error along the line of sight, dC the broadcast
// clock error (m), and I, T the true ionosphere and troposphere (ErrorWorld). The code
// phase transmitted at t_sv is (t_sv mod 1 ms) * 1.023 MHz; the carrier phase in the
// down-converted samples is f_IF t_rcv - f_L1 P_carr / c.
#include <Eigen/Core>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/iono_utc.hpp"
#include "signals/sim/error_world.hpp"

namespace deepnav {

/// The receiver at one instant, as the synthesizer knows it from the trajectory and the clock model.
struct ReceiverInstant {
  double t_rcv_rel_s = 0.0;  ///< receiver clock reading minus the reference epoch (whole ms of the start)
  GpsTime t_true{};          ///< true GPS time of reception
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  wgs84::Llh llh{};
  double clock_bias_s = 0.0;
  double clock_drift_sps = 0.0;
};

/// The signal of one satellite at one receiver instant.
struct SatelliteInstant {
  double code_chips = 0.0;      ///< (t_sv - reference epoch) * 1.023e6: unwrapped code phase
  double carrier_cycles = 0.0;  ///< carrier phase in the samples, IF term included, unwrapped
  double doppler_hz = 0.0;      ///< -f_L1 dP_carr/dt / c (excluding the IF)
  double elevation_rad = 0.0;
  double azimuth_rad = 0.0;
  double range_m = 0.0;  ///< geometric range to the broadcast orbit (light time, Sagnac)
  double range_rate_mps = 0.0;
  double pseudorange_m = 0.0;  ///< code pseudorange as the receiver would measure it
  double iono_m = 0.0;         ///< L1 group delay (the truth the signal carries)
  double tropo_m = 0.0;        ///< troposphere delay (the truth the signal carries)
  double sat_clock_m = 0.0;    ///< c * dts_L1 from the broadcast clock (Galileo: c (dts_E1 + GGTO))
  // What the receiver's models say and the error world adds (ErrorWorld):
  double iono_broadcast_m = 0.0;   ///< Klobuchar for this look (0 without broadcast parameters)
  double tropo_model_m = 0.0;      ///< the receiver's standard-atmosphere troposphere for this look
  double orbit_m = 0.0;            ///< true minus broadcast range (broadcast orbit error on the line of sight)
  double sat_clock_error_m = 0.0;  ///< c (dts_true - dts_broadcast): the signal's clock is sat_clock_m + this
  double antenna_gain_db = 0.0;    ///< receiver antenna gain towards the satellite (0 at the zenith)
};

/// Evaluates the signal of the satellite described by `eph` at receiver instant `rx` in
/// the error world `world`; `iono` are the broadcast ionosphere parameters.
SatelliteInstant evaluate_satellite(const Ephemeris& eph, const IonoParameters& iono, const ErrorWorld& world,
                                    const ReceiverInstant& rx, double if_hz);
/// A Galileo satellite's E1 signal: the orbit and the clock (dts_E1 = e1_clock_correction_s)
/// run on GST, gst_minus_gpst_s (the GGTO) apart from the GPS time of the receiver's clock.
/// The code phase is the GST the satellite's clock reads at transmission, so the pseudorange
/// and sat_clock_m carry c (dts_E1 + GGTO). `iono` (Klobuchar) is the basis of the true
/// ionosphere as for GPS: E1 shares L1's frequency.
SatelliteInstant evaluate_satellite(const galileo::GalileoEphemeris& eph, double gst_minus_gpst_s,
                                    const IonoParameters& iono, const ErrorWorld& world, const ReceiverInstant& rx,
                                    double if_hz);
/// The same with the broadcast models as truth (error preset none).
SatelliteInstant evaluate_satellite(const Ephemeris& eph, const IonoParameters& iono, AtmosphereSwitches atmosphere,
                                    const ReceiverInstant& rx, double if_hz);

}  // namespace deepnav
