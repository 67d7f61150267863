#include "aiding/gnss_coupling.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "aiding/measurement_models.hpp"
#include "ins/rotations.hpp"
#include "receiver/pvt/range_model.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {

NavigatorConfig navigator_config(const CouplingSettings& settings) {
  NavigatorConfig nc;
  nc.noise = process_noise_from(settings.imu, settings.oscillator);
  nc.lever_arm_imu_to_antenna_b_m = settings.lever_arm_imu_to_antenna_b_m;
  nc.gate_sigma = settings.gate_sigma;
  nc.troposphere = settings.troposphere;
  nc.ionosphere = settings.ionosphere;
  return nc;
}

GnssFix alignment_fix(const PvtSolution& pvt, double t_s, double position_sigma_scale_m) {
  GnssFix fix;
  fix.t_s = t_s;
  fix.r_antenna_ecef_m = pvt.r_ecef_m;
  fix.v_antenna_ecef_mps = pvt.v_ecef_mps;
  fix.clock_bias_m = pvt.clock_bias_m;
  fix.clock_drift_mps = pvt.clock_drift_mps;
  fix.horizontal_sigma_m = std::max(1.0, pvt.dops.hdop * position_sigma_scale_m);
  fix.vertical_sigma_m = std::max(1.5, pvt.dops.vdop * position_sigma_scale_m);
  return fix;
}

AidedNavigator start_navigator(const InsStart& start, const GnssFix& fix, const NavigatorConfig& config,
                               double clock_step_m, double log_t_s) {
  // The start is at the initializer's last IMU sample, next to the fix: the clock drifts
  // over the difference.
  const double dt = start.state.t_s - fix.t_s;
  const double bias = fix.clock_bias_m + fix.clock_drift_mps * dt + clock_step_m;
  const EulerAngles e = euler_from_quaternion(start.state.q_b_n);
  spdlog::info("t = {:.2f} s: INS started ({}): roll {:.2f} pitch {:.2f} yaw {:.2f} deg", log_t_s, start.method,
               e.roll_rad * 180.0 / M_PI, e.pitch_rad * 180.0 / M_PI, e.yaw_rad * 180.0 / M_PI);
  return AidedNavigator(start.state, bias, fix.clock_drift_mps, config, start.uncertainty);
}

KalmanUpdate loose_update(AidedNavigator& nav, const LooseFix& fix, double position_sigma_scale_m) {
  const double dt = fix.t_s - nav.time_s();
  const PvtSolution& pvt = fix.pvt;
  return nav.update_position_velocity(pvt.r_ecef_m, pvt.v_ecef_mps,
                                      pvt_position_sigma_ned_m(pvt.dops.hdop, pvt.dops.vdop, position_sigma_scale_m),
                                      fix.velocity_sigma_ned_mps, dt, dt + fix.doppler_offset_s);
}

TightRows tight_rows(const AidedNavigator& nav, const RangeEpoch& epoch, const AtmosphereModels& atmosphere,
                     double elevation_mask_rad, const PseudorangeWeighting& weighting) {
  TightRows out;
  const double dt = epoch.t_s - nav.time_s();
  const double bias = nav.clock_bias_m() + nav.clock_drift_mps() * dt;
  for (const RangeObservation& o : epoch.satellites) {
    const auto predict = [&](const GpsTime& t_rx, double clock_bias_m, const Eigen::Vector3d& r_ecef_m,
                             const Eigen::Vector3d& v_ecef_mps) {
      return std::visit(
          [&](const auto& eph) {
            return predict_range(eph, t_rx, clock_bias_m, r_ecef_m, v_ecef_mps, epoch.iono, atmosphere);
          },
          o.ephemeris);
    };
    RangeMeasurement m;
    m.satellite = o.satellite;
    m.time_offset_s = dt;
    m.geometry = predict(epoch.t_rx, bias, nav.antenna_ecef_at(epoch.t_s), nav.antenna_velocity_ecef_mps());
    if (m.geometry.elevation_rad < elevation_mask_rad) {
      out.below_mask.push_back(m);
      continue;
    }
    if (o.pseudorange_m) {
      m.pseudorange_m = o.pseudorange_m;
      m.pseudorange_sigma_m =
          std::hypot(weighting.scale * scalar_pseudorange_sigma_m(weighting.errors, m.geometry.elevation_rad,
                                                                  o.cn0_dbhz, weighting.row_interval_s),
                     o.offset_sigma_m);
    }
    if (o.doppler_hz) {
      m.rate_mps = -gps::kL1Wavelength_m * *o.doppler_hz;
      m.rate_sigma_mps = o.rate_sigma_mps;
      // Predicted at the Doppler's time: the satellite's geometry, the clock and the INS
      // velocity there.
      const double t_rate = epoch.t_s + o.doppler_offset_s;
      m.rate_at_own_time = true;
      m.rate_time_offset_s = t_rate - nav.time_s();
      m.rate_geometry =
          predict(epoch.t_rx.plus_seconds(o.doppler_offset_s), bias + nav.clock_drift_mps() * o.doppler_offset_s,
                  nav.antenna_ecef_at(t_rate), nav.antenna_velocity_ecef_at(t_rate));
    }
    if (!m.pseudorange_m && !m.rate_mps) continue;  // nothing measured
    out.used.push_back(m);
  }
  return out;
}

}  // namespace deepnav::aiding
