#include "receiver/pvt/range_model.hpp"

#include <cmath>
#include <utility>

#include "ins/frames.hpp"
#include "ins/wgs84.hpp"
#include "signals/atmosphere.hpp"
#include "signals/galileo/gst.hpp"

namespace deepnav {
namespace {

struct Atmosphere {
  double iono_m = 0.0, tropo_m = 0.0;
  double elevation_rad = 0.0, azimuth_rad = 0.0;
};

Atmosphere atmosphere_at(const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& r_sat_ecef_m,
                         const IonoParameters& iono, const AtmosphereModels& models, double sow) {
  Atmosphere a;
  const wgs84::Llh llh = wgs84::ecef_to_llh(r_rx_ecef_m);
  const LookAngles la = look_angles(llh, r_rx_ecef_m, r_sat_ecef_m);
  a.elevation_rad = la.elevation_rad;
  a.azimuth_rad = la.azimuth_rad;
  a.iono_m = models.ionosphere_delay_m(iono, llh.lat_rad, llh.lon_rad, la.azimuth_rad, la.elevation_rad, sow);
  if (la.elevation_rad > 0.0) a.tropo_m = models.troposphere_delay_m(llh.lat_rad, llh.height_m, la.elevation_rad);
  return a;
}

/// The prediction for any system: `clock_and_state(t_tx)` gives the satellite's clock
/// correction (s) and its state at the transmit time t_tx (GPS time).
template <typename ClockAndState>
RangePrediction predict(ClockAndState clock_and_state, const GpsTime& t_rx, double clock_bias_m,
                        const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& v_rx_ecef_mps,
                        const IonoParameters& iono, const AtmosphereModels& models) {
  constexpr double c = wgs84::kSpeedOfLight_mps;
  RangePrediction p;
  // True receive time, then two fixed-point passes on the flight time (converges to
  // well below a millimetre: the range changes by < 1 km over the correction).
  const GpsTime t_true = t_rx.plus_seconds(-clock_bias_m / c);
  double tau = 0.075;
  for (int pass = 0; pass < 3; ++pass) {
    const GpsTime t_tx = t_true.plus_seconds(-tau);
    const auto [dts, s] = clock_and_state(t_tx);
    p.r_sat_ecef_m = earth_rotation_corrected(s.r_ecef_m, tau);
    p.v_sat_ecef_mps = earth_rotation_corrected(s.v_ecef_mps, tau);
    p.satellite_clock_m = c * dts;
    p.satellite_drift_mps = c * s.clock_drift_sps;
    const Eigen::Vector3d d = p.r_sat_ecef_m - r_rx_ecef_m;
    p.geometric_range_m = d.norm();
    p.los_ecef = d / p.geometric_range_m;
    tau = p.geometric_range_m / c;
  }
  // The flight time changes at k = tau' (light-time equation with the Sagnac rotation):
  // range' (1 + k) = u.(v_sat - v_rx).
  const Eigen::Vector3d z_cross_r(-p.r_sat_ecef_m.y(), p.r_sat_ecef_m.x(), 0.0);
  p.light_time_factor =
      1.0 / (1.0 + (p.los_ecef.dot(p.v_sat_ecef_mps) + wgs84::kEarthRate_radps * p.los_ecef.dot(z_cross_r)) / c);
  const Atmosphere now = atmosphere_at(r_rx_ecef_m, p.r_sat_ecef_m, iono, models, t_rx.sow);
  p.elevation_rad = now.elevation_rad;
  p.azimuth_rad = now.azimuth_rad;
  p.atmosphere_m = now.iono_m + now.tropo_m;
  // The atmosphere's rate over +-0.5 s (both models are smooth over seconds); the carrier
  // is advanced by the ionosphere as much as the code is delayed.
  constexpr double h = 0.5;
  const Atmosphere before =
      atmosphere_at(r_rx_ecef_m - h * v_rx_ecef_mps, p.r_sat_ecef_m - h * p.v_sat_ecef_mps, iono, models, t_rx.sow - h);
  const Atmosphere after =
      atmosphere_at(r_rx_ecef_m + h * v_rx_ecef_mps, p.r_sat_ecef_m + h * p.v_sat_ecef_mps, iono, models, t_rx.sow + h);
  p.carrier_atmosphere_rate_mps = ((after.tropo_m - after.iono_m) - (before.tropo_m - before.iono_m)) / (2.0 * h);
  p.ionosphere_m = now.iono_m;
  p.ionosphere_rate_mps = (after.iono_m - before.iono_m) / (2.0 * h);
  p.troposphere_mapping = troposphere_mapping(now.elevation_rad);
  p.troposphere_mapping_rate_per_s =
      (troposphere_mapping(after.elevation_rad) - troposphere_mapping(before.elevation_rad)) / (2.0 * h);
  return p;
}

}  // namespace

RangePrediction predict_range(const Ephemeris& eph, const GpsTime& t_rx, double clock_bias_m,
                              const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& v_rx_ecef_mps,
                              const IonoParameters& iono, const AtmosphereModels& models) {
  const auto clock_and_state = [&eph](const GpsTime& t_tx) {
    return std::pair{l1_clock_correction_s(eph, t_tx), satellite_state(eph, t_tx)};
  };
  return predict(clock_and_state, t_rx, clock_bias_m, r_rx_ecef_m, v_rx_ecef_mps, iono, models);
}

RangePrediction predict_range(const galileo::GalileoEphemeris& eph, const GpsTime& t_rx, double clock_bias_m,
                              const Eigen::Vector3d& r_rx_ecef_m, const Eigen::Vector3d& v_rx_ecef_mps,
                              const IonoParameters& iono, const AtmosphereModels& models) {
  // GPS time labels read as GST ones, as the PVT does: the GGTO (tens of ns) moves a satellite
  // by a tenth of a millimetre; the clock offset it leaves is the caller's (its Galileo rows'
  // system offset).
  const auto clock_and_state = [&eph](const GpsTime& t_tx) {
    const galileo::GstTime t = galileo::gst_from_gps_time(t_tx);
    return std::pair{galileo::e1_clock_correction_s(eph, t), galileo::satellite_state(eph, t)};
  };
  return predict(clock_and_state, t_rx, clock_bias_m, r_rx_ecef_m, v_rx_ecef_mps, iono, models);
}

}  // namespace deepnav
