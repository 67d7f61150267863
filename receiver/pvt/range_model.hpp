#pragma once
// Predicted pseudorange and pseudorange rate of one satellite for a receiver position,
// velocity and clock: what a tightly coupled filter compares with the measurements and
// what an ultra-tight receiver steers its NCOs by. The same corrections as the PVT
// solution: satellite clock with relativity and TGD, orbit at the transmit time, Earth
// rotation during the flight, and the receiver's atmosphere models (AtmosphereModels:
// Klobuchar ionosphere and Saastamoinen troposphere by default).
//
// The rate is the rate of the carrier the receiver tracks, against its own clock (what
// -lambda * Doppler measures), to a small fraction of a millimetre per second:
//   rate = (u.(v_sat - v_rx) / (1 + k) + c dt' - c dts' + d(T - I)/dt) / (1 + dt')
// with k = (u.v_sat + omega_e u.(z x r_sat)) / c the change of the flight time (light-time
// equation with Sagnac; up to 5e-6, a few mm/s at low elevation), the atmosphere's rate
// with the carrier's ionospheric advance (up to cm/s near the horizon, and from the
// troposphere as the receiver climbs), and the receiver clock's own rate (a Doppler is
// counted in receiver seconds). Left out, each is a per-satellite bias of the Doppler
// rows that a tight filter turns into a velocity and, against its pseudoranges, a
// steady position error.
#include <Eigen/Core>
#include <optional>

#include "ins/gps_time.hpp"
#include "receiver/pvt/atmosphere_models.hpp"
#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/gps_constants.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

struct RangePrediction {
  Eigen::Vector3d r_sat_ecef_m = Eigen::Vector3d::Zero();  ///< at transmit time, in the ECEF frame of the receive time
  Eigen::Vector3d v_sat_ecef_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d los_ecef = Eigen::Vector3d::Zero();  ///< unit vector receiver -> satellite
  double geometric_range_m = 0.0;
  double satellite_clock_m = 0.0;            ///< c * satellite clock offset (subtracted from the range)
  double satellite_drift_mps = 0.0;          ///< c * satellite clock drift
  double atmosphere_m = 0.0;                 ///< ionosphere + troposphere delay
  double carrier_atmosphere_rate_mps = 0.0;  ///< d(troposphere - ionosphere)/dt: the carrier's
  double light_time_factor = 1.0;            ///< 1 / (1 + k), k the flight time's rate (see above)
  double elevation_rad = 0.0;
  double azimuth_rad = 0.0;
  /// The troposphere model's mapping function at the satellite's elevation and its rate as
  /// the satellite rises or sets (1/s): how a zenith delay left by the model reaches this
  /// pseudorange and its rate.
  double troposphere_mapping = 1.0;
  double troposphere_mapping_rate_per_s = 0.0;
  /// The ionosphere model's code delay at this look (m, part of atmosphere_m) and its rate
  /// (m/s; the carrier is advanced at minus this rate): how an error in the scale of the
  /// model's delay reaches this pseudorange and the carrier's rate.
  double ionosphere_m = 0.0;
  double ionosphere_rate_mps = 0.0;

  /// Pseudorange with the receiver clock bias c*dt (m).
  double pseudorange_m(double clock_bias_m) const {
    return geometric_range_m + clock_bias_m - satellite_clock_m + atmosphere_m;
  }
  /// Pseudorange rate with the receiver velocity and clock drift c*dt' (m/s); the carrier
  /// Doppler is -rate / lambda.
  double pseudorange_rate_mps(const Eigen::Vector3d& v_rx_ecef_mps, double clock_drift_mps) const {
    const double true_time_rate = light_time_factor * los_ecef.dot(v_sat_ecef_mps - v_rx_ecef_mps) + clock_drift_mps -
                                  satellite_drift_mps + carrier_atmosphere_rate_mps;
    return true_time_rate / (1.0 + clock_drift_mps / gps::kSpeedOfLight_mps);
  }
};

/// Prediction at receiver time t_rx (receiver clock corrected by `clock_bias_m`) for a
/// receiver at r_rx moving with v_rx (the velocity only moves the atmosphere's rate).
/// `models`: the receiver's choice (GnssReceiver::atmosphere(), the same the PVT
/// applies); `iono` is used only with the Klobuchar model and may be invalid (no
/// ionosphere applied).
RangePrediction predict_range(const Ephemeris& eph, const GpsTime& t_rx, double clock_bias_m,
                              const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& v_rx_ecef_mps,
                              const IonoParameters& iono, const AtmosphereModels& models = {});
/// The same for a Galileo satellite (E1 clock with BGD(E1,E5b)). `clock_bias_m` is the clock
/// its measurements see: the GPS clock plus the Galileo system offset (GGTO and the
/// receiver's inter-system bias). The Klobuchar model stands in for NeQuick-G, as in the PVT.
RangePrediction predict_range(const galileo::GalileoEphemeris& eph, const GpsTime& t_rx, double clock_bias_m,
                              const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& v_rx_ecef_mps,
                              const IonoParameters& iono, const AtmosphereModels& models = {});

}  // namespace deepnav
