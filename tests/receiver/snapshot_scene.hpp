#pragma once
// Snapshot measurements for the coarse-time tests: code phases (transmit time modulo
// 1 ms) and Dopplers of the satellites above 5 degrees, made from the broadcast
// ephemerides of data/brdc0010.22n by the signal model of the IF synthesizer
// (signals/sim/satellite_signal_model.hpp: light time with Sagnac, satellite clock,
// Klobuchar ionosphere and Saastamoinen troposphere as the truth) for a static receiver
// at a known place, time and clock, with Gaussian noise of fixed seeds.
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "receiver/pvt/coarse_time_fit.hpp"
#include "receiver/pvt/doppler_position.hpp"
#include "receiver/pvt/snapshot_measurement.hpp"
#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/satellite_signal_model.hpp"

namespace deepnav::snapshot_test {

inline constexpr double kDeg = 3.14159265358979323846 / 180.0;

inline const NavData& broadcast_navigation() {
  static const NavData nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  return nav;
}

struct SceneSpec {
  wgs84::Llh place{};
  GpsTime t_true{2190, 525600.0};  ///< true GPS time of the receive sample
  double clock_bias_s = 3.21e-4;   ///< receiver clock minus GPS time at the sample
  double clock_drift_sps = 1e-7;
  double code_noise_m = 3.0;       ///< 1 sigma of the code phases, as a range
  double doppler_noise_hz = 15.0;  ///< 1 sigma of the Dopplers
  double min_elevation_rad = 5.0 * kDeg;
  std::uint64_t seed = 1;
};

struct Scene {
  SceneSpec spec;
  Eigen::Vector3d r_true = Eigen::Vector3d::Zero();
  GpsTime t_receiver{};  ///< the receiver clock's reading of the sample: t_true + clock bias
  std::map<int, Ephemeris> ephemerides;
  std::vector<SnapshotMeasurement> measurements;
  std::map<int, double> elevation_rad;
};

inline Scene make_scene(const SceneSpec& spec) {
  Scene s;
  s.spec = spec;
  const NavData& nav = broadcast_navigation();
  ReceiverInstant rx;
  rx.llh = spec.place;
  rx.r_ecef_m = wgs84::llh_to_ecef(spec.place);
  rx.clock_bias_s = spec.clock_bias_s;
  rx.clock_drift_sps = spec.clock_drift_sps;
  rx.t_true = spec.t_true;
  s.r_true = rx.r_ecef_m;
  s.t_receiver = spec.t_true.plus_seconds(spec.clock_bias_s);
  std::mt19937_64 rng(spec.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
    const Ephemeris* eph = nav.select(prn, spec.t_true);
    if (!eph) continue;
    const SatelliteInstant si = evaluate_satellite(*eph, nav.iono, AtmosphereSwitches{true, true}, rx, 0.0);
    if (si.elevation_rad < spec.min_elevation_rad) continue;
    s.ephemerides[prn] = *eph;
    s.elevation_rad[prn] = si.elevation_rad;
    // t_sv = t_receiver - P / c, reduced modulo 1 ms before the seconds of week join in.
    const double pseudorange_m = si.pseudorange_m + spec.code_noise_m * normal(rng);
    double t_sv_s = std::fmod(s.t_receiver.sow, 1e-3) - pseudorange_m / gps::kSpeedOfLight_mps;
    t_sv_s = std::fmod(t_sv_s, 1e-3);
    if (t_sv_s < 0.0) t_sv_s += 1e-3;
    SnapshotMeasurement m;
    m.prn = prn;
    m.code_phase_chips = std::fmod(t_sv_s * gps::kCodeRate_cps, gps::kCodeLength_chips);
    m.doppler_hz = si.doppler_hz + spec.doppler_noise_hz * normal(rng);
    m.cn0_dbhz = 45.0;
    s.measurements.push_back(m);
  }
  return s;
}

/// The scene's satellites as the coarse-time fit takes them, with the time hint `t_hint`.
inline std::vector<CoarseTimeSatellite> fit_satellites(const Scene& s, const GpsTime& t_hint, double sigma_m = 5.0) {
  std::vector<CoarseTimeSatellite> out;
  for (const auto& m : s.measurements)
    out.push_back({m.prn, &s.ephemerides.at(m.prn), submillisecond_pseudorange_m(m.code_phase_chips, t_hint), sigma_m});
  return out;
}

inline std::vector<DopplerSatellite> doppler_satellites(const Scene& s) {
  std::vector<DopplerSatellite> out;
  for (const auto& m : s.measurements) out.push_back({m.prn, &s.ephemerides.at(m.prn), *m.doppler_hz});
  return out;
}

/// `r` moved over the ellipsoid by `distance_m` towards `azimuth_rad` (locally flat), height kept.
inline Eigen::Vector3d moved(const Eigen::Vector3d& r, double distance_m, double azimuth_rad) {
  wgs84::Llh llh = wgs84::ecef_to_llh(r);
  llh.lat_rad += distance_m * std::cos(azimuth_rad) / wgs84::meridian_radius_m(llh.lat_rad);
  llh.lon_rad += distance_m * std::sin(azimuth_rad) / (wgs84::transverse_radius_m(llh.lat_rad) * std::cos(llh.lat_rad));
  return wgs84::llh_to_ecef(llh);
}

/// The places of the tests: several latitudes and both hemispheres, one high up.
inline std::vector<wgs84::Llh> test_places() {
  return {{37.5665 * kDeg, 126.9780 * kDeg, 40.0},
          {48.8500 * kDeg, 2.3500 * kDeg, 100.0},
          {-33.9000 * kDeg, 18.4000 * kDeg, 10.0},
          {64.1000 * kDeg, -21.9000 * kDeg, 20.0},
          {-0.2000 * kDeg, -78.5000 * kDeg, 2800.0}};
}

}  // namespace deepnav::snapshot_test
