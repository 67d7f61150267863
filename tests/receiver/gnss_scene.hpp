#pragma once
// GPS and Galileo pseudoranges and Dopplers of a static receiver computed from real
// broadcast ephemerides: GPS from data/brdc0010.22n (2022-01-01), Galileo from
// data/galileo_20220220.rnx (2022-02-19 20:00 - 2022-02-20), whose records are moved back by
// seven whole weeks so that they fall on 2022-01-01 20:00-24:00 with the GPS ones (a
// whole-week move leaves every orbit and clock as it was within its week). The epoch is
// 23:50, when the file holds a batch already sent for most satellites.
//
// The ranges are geometric: light time with the Earth's rotation during the flight, the
// broadcast satellite clocks (with relativity and the L1 / E1 group delay), a receiver clock
// bias and drift, and an offset of the Galileo measurements' clock (GGTO plus the receiver's
// inter-system bias); no atmosphere, so the fixes use AtmosphereModels none.
#include <Eigen/Core>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "ins/frames.hpp"
#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::test {

inline constexpr double kSceneDeg = M_PI / 180.0;
inline constexpr int kGalileoWeekShift = 7;  ///< 2022-02-19 less 7 weeks is 2022-01-01

struct GnssScene {
  NavData gps_nav, galileo_nav;
  std::map<int, Ephemeris> gps;
  std::map<int, galileo::GalileoEphemeris> galileo;
  GpsTime t_rx{2190, 604200.0};  ///< 2022-01-01 23:50 GPS time (receiver clock)
  /// Helsinki: six Galileo satellites above 10 degrees with a batch sent before the epoch.
  wgs84::Llh llh{60.1699 * kSceneDeg, 24.9384 * kSceneDeg, 20.0};
  Eigen::Vector3d r_ecef_m = wgs84::llh_to_ecef(llh);
  double clock_bias_s = 1e-4;
  double clock_drift_sps = 5e-7;
  double galileo_offset_m = 23.0;  ///< c * (Galileo measurements' clock - GPS clock)
  double elevation_mask_deg = 10.0;

  GnssScene() {
    gps_nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
    galileo_nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/galileo_20220220.rnx");
    for (int prn = 1; prn <= 32; ++prn) {
      const Ephemeris* e = gps_nav.select(prn, t_rx);
      if (e && e->healthy() && elevation_deg(state(*e, t_rx).r_ecef_m) > elevation_mask_deg) gps[prn] = *e;
    }
    // I/NAV data sets, healthy on E1-B, the latest toe before the epoch and within 3 h of it
    // (a Galileo batch's toe is when it starts being sent; RTKLIB takes none from the future).
    const galileo::GstTime t_gst = galileo::gst_from_gps_time(t_rx);
    for (galileo::GalileoEphemeris e : galileo_nav.galileo_ephemerides) {
      e.week -= kGalileoWeekShift;
      if ((e.data_sources & 1) == 0 || !e.healthy_on_e1b()) continue;
      const double age = t_gst.seconds_since(galileo::GstTime{e.week, e.orbit.toe_s});
      if (age <= 0.0 || age > 3 * 3600.0) continue;
      const auto it = galileo.find(e.prn);
      if (it != galileo.end() && t_gst.seconds_since(galileo::GstTime{it->second.week, it->second.orbit.toe_s}) <= age)
        continue;
      galileo[e.prn] = e;
    }
    for (auto it = galileo.begin(); it != galileo.end();)
      it = elevation_deg(state(it->second, t_rx).r_ecef_m) > elevation_mask_deg ? std::next(it) : galileo.erase(it);
  }

  static SatelliteState state(const Ephemeris& e, const GpsTime& t) { return satellite_state(e, t); }
  static SatelliteState state(const galileo::GalileoEphemeris& e, const GpsTime& t) {
    return galileo::satellite_state(e, galileo::gst_from_gps_time(t));
  }
  static double clock_s(const Ephemeris& e, const GpsTime& t) { return l1_clock_correction_s(e, t); }
  static double clock_s(const galileo::GalileoEphemeris& e, const GpsTime& t) {
    return galileo::e1_clock_correction_s(e, galileo::gst_from_gps_time(t));
  }

  double elevation_deg(const Eigen::Vector3d& r_sat) const {
    return look_angles(llh, r_ecef_m, r_sat).elevation_rad / kSceneDeg;
  }

  /// Pseudorange at receiver clock time t (m) of the satellite of `e`: the transmit time by
  /// light-time iteration in the ECEF frame of the receive time.
  template <typename Eph>
  double pseudorange_m(const Eph& e, const GpsTime& t, double receiver_clock_m) const {
    constexpr double c = gps::kSpeedOfLight_mps;
    const double dt_rx_s = receiver_clock_m / c;
    const GpsTime t_true = t.plus_seconds(-dt_rx_s);
    double tau = 0.07, range = 0.0;
    for (int pass = 0; pass < 6; ++pass) {
      const GpsTime t_tx = t_true.plus_seconds(-tau);
      const Eigen::Vector3d r_sat = earth_rotation_corrected(state(e, t_tx).r_ecef_m, tau);
      range = (r_sat - r_ecef_m).norm();
      tau = range / c;
    }
    const GpsTime t_tx = t_true.plus_seconds(-tau);
    return range + receiver_clock_m - c * clock_s(e, t_tx);
  }

  /// One system's observations at receiver time t with Gaussian noise of sigma `noise_m`
  /// (m) on the pseudoranges; Dopplers from the pseudoranges' change over +-0.5 s.
  template <typename Eph>
  void observe(const std::map<int, Eph>& ephs, GnssSystem system, const GpsTime& t, double noise_m,
               std::mt19937_64& rng, std::vector<PseudorangeObservation>& out) const {
    std::normal_distribution<double> n(0.0, 1.0);
    constexpr double c = gps::kSpeedOfLight_mps;
    const double offset_m = system == GnssSystem::galileo ? galileo_offset_m : 0.0;
    const auto clock_at = [&](double dt) { return c * (clock_bias_s + clock_drift_sps * dt) + offset_m; };
    for (const auto& [prn, e] : ephs) {
      const double pr = pseudorange_m(e, t, clock_at(0.0));
      const double rate =
          pseudorange_m(e, t.plus_seconds(0.5), clock_at(0.5)) - pseudorange_m(e, t.plus_seconds(-0.5), clock_at(-0.5));
      PseudorangeObservation o;
      o.prn = prn;
      o.system = system;
      o.pseudorange_m = pr + noise_m * n(rng);
      o.doppler_hz = -rate / gps::kL1Wavelength_m;
      o.cn0_dbhz = 45.0;
      out.push_back(o);
    }
  }

  std::vector<PseudorangeObservation> gps_obs(const GpsTime& t, double noise_m, std::mt19937_64& rng) const {
    std::vector<PseudorangeObservation> out;
    observe(gps, GnssSystem::gps, t, noise_m, rng, out);
    return out;
  }
  std::vector<PseudorangeObservation> galileo_obs(const GpsTime& t, double noise_m, std::mt19937_64& rng) const {
    std::vector<PseudorangeObservation> out;
    observe(galileo, GnssSystem::galileo, t, noise_m, rng, out);
    return out;
  }
  std::vector<PseudorangeObservation> both_obs(const GpsTime& t, double noise_m, std::mt19937_64& rng) const {
    std::vector<PseudorangeObservation> out = gps_obs(t, noise_m, rng);
    observe(galileo, GnssSystem::galileo, t, noise_m, rng, out);
    return out;
  }
};

/// A solver without atmosphere models (the scene's ranges have none).
inline PvtSolver vacuum_solver(PvtConfig config = {}) {
  config.elevation_mask_rad = 5.0 * kSceneDeg;
  return PvtSolver(config, AtmosphereModels{IonosphereModel::none, TroposphereModel::none});
}

}  // namespace deepnav::test
