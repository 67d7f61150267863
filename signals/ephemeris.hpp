#pragma once
// Broadcast ephemeris and clock of one GPS satellite (IS-GPS-200 subframes 1-3)
// and the user algorithms of IS-GPS-200 Table 20-IV.
#include <Eigen/Core>

#include "ins/gps_time.hpp"

namespace deepnav {

/// Field names and units follow IS-GPS-200 (angles in radians here, converted from
/// semicircles at the edges: LNAV decoding and RINEX reading).
struct Ephemeris {
  int prn = 0;
  int week = 0;  ///< full GPS week number of toe (not modulo 1024)
  int iodc = 0;
  int iode = 0;       ///< IODE of subframes 2 and 3 (must equal IODC's 8 LSBs)
  int health = 0;     ///< 6-bit SV health
  int ura_index = 0;  ///< URA index N (0..15)
  int code_on_l2 = 1;
  int l2p_data_flag = 0;
  int fit_interval_flag = 0;
  double toc_s = 0.0;  ///< clock reference time, seconds of week
  double af0_s = 0.0, af1_sps = 0.0, af2_sps2 = 0.0;
  double tgd_s = 0.0;
  double toe_s = 0.0;   ///< ephemeris reference time, seconds of week
  double sqrt_a = 0.0;  ///< sqrt(m)
  double e = 0.0;
  double m0_rad = 0.0, delta_n_radps = 0.0;
  double omega0_rad = 0.0, omega_dot_radps = 0.0;
  double i0_rad = 0.0, idot_radps = 0.0;
  double omega_rad = 0.0;  ///< argument of perigee
  double cuc_rad = 0.0, cus_rad = 0.0, crc_m = 0.0, crs_m = 0.0, cic_rad = 0.0, cis_rad = 0.0;
  double aodo_s = 0.0;               ///< age of data offset (subframe 2)
  double transmission_time_s = 0.0;  ///< when known (RINEX), seconds of week
  /// Whether transmission_time_s holds a value (RINEX writes 0.9999e9 when it does not).
  /// The value may be negative when it refers to the week before toe's week (RINEX 3).
  bool transmission_time_known = false;

  bool healthy() const { return health == 0; }
};

/// Satellite state at GPS time t (transmission time, in the ECEF frame at that time).
struct SatelliteState {
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  double clock_bias_s = 0.0;  ///< af0 + af1 dt + af2 dt^2 + relativistic term (TGD not included)
  double clock_drift_sps = 0.0;
  double relativistic_s = 0.0;  ///< the relativistic part of clock_bias_s
};

/// Position, velocity and clock per IS-GPS-200 Table 20-IV at GPS time t. tk = t - toe uses the
/// weeks when t and toe are within half a week of each other (so toe in the previous or next
/// week works); otherwise the weeks are taken as unreliable (unknown, or off by 1024-week
/// rollovers) and IS-GPS-200's end/start-of-week fold of the seconds of week applies.
SatelliteState satellite_state(const Ephemeris& eph, const GpsTime& t);

/// Satellite clock correction for L1 C/A users: clock_bias - TGD (IS-GPS-200 20.3.3.3.3.2).
double l1_clock_correction_s(const Ephemeris& eph, const GpsTime& t);

/// Rotates a satellite position from the ECEF frame at transmission time into the ECEF frame at
/// reception time, flight time tau_s later (Sagnac / Earth-rotation correction).
Eigen::Vector3d earth_rotation_corrected(const Eigen::Vector3d& r_ecef_at_tx, double tau_s);

/// Curve fit interval of the data set (IS-GPS-200 20.3.3.4.3.1 and Tables 20-XI/XII): 4 h when
/// the fit interval flag is 0, otherwise the extended interval that the IODC indicates.
/// The data set is valid from toe - interval/2 to toe + interval/2.
double fit_interval_s(const Ephemeris& eph);

}  // namespace deepnav
