#pragma once
// Broadcast ephemeris, clock and status of one Galileo satellite (Galileo OS SIS ICD 5.1.1 -
// 5.1.9) and the user algorithms: the Keplerian model GPS uses, evaluated with Galileo's
// constants, the satellite clock with its relativistic term, and the E1 group delay.
#include <optional>

#include "signals/ephemeris.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/kepler_orbit.hpp"

namespace deepnav::galileo {

/// Signal health status (2 bits) of a component (ICD 5.1.9.3).
enum class SignalHealth { kOk = 0, kOutOfService = 1, kExtendedOperations = 2, kInTest = 3 };

/// Health and data validity of one signal (E1-B, E5a or E5b).
struct SignalStatus {
  int health = 0;             ///< signal health status HS (0: OK)
  bool data_invalid = false;  ///< data validity status DVS: working without guarantee
  bool usable() const { return health == 0 && !data_invalid; }
};

struct GalileoEphemeris {
  int prn = 0;                                        ///< SVID, 1..36 in the message (codes exist for 1..50)
  int week = 0;                                       ///< full GST week of toe
  int iod_nav = 0;                                    ///< issue of data of the batch, 10 bits
  double toc_s = 0;                                   ///< clock reference time, seconds of week
  double af0_s = 0.0, af1_sps = 0.0, af2_sps2 = 0.0;  ///< clock for the E1,E5b pair (I/NAV)
  KeplerElements orbit;
  double bgd_e1e5a_s = 0.0;  ///< broadcast group delay E1,E5a
  double bgd_e1e5b_s = 0.0;  ///< broadcast group delay E1,E5b
  int sisa_index = 255;      ///< signal-in-space accuracy index; 255: no accuracy prediction (NAPA)
  SignalStatus e1b, e5a, e5b;
  /// RINEX "data sources" bits where the data set came from a file (bit 0: I/NAV E1-B, 1:
  /// F/NAV E5a-I, 2: I/NAV E5b-I, 8: clock for E5a,E1, 9: clock for E5b,E1); 0 when decoded.
  int data_sources = 0;
  double transmission_time_s = 0.0;  ///< seconds of week, when known
  bool transmission_time_known = false;

  /// Whether the clock refers to the E1,E5a pair (F/NAV) rather than E1,E5b (I/NAV).
  bool clock_for_e1e5a() const { return (data_sources & (1 << 8)) != 0; }
  /// Whether the E1-B signal and its navigation data may be used.
  bool healthy_on_e1b() const { return e1b.usable(); }
};

/// Satellite state at GST t: the model of ICD Table 64 in the ECEF frame at t; clock_bias_s
/// is af0 + af1 dt + af2 dt^2 plus the relativistic term F e sqrt(A) sin E (ICD 5.1.4), no
/// group delay. Weeks are used as for GPS: toe a week before or after t works.
SatelliteState satellite_state(const GalileoEphemeris& eph, const GstTime& t);

/// Satellite clock correction for a single-frequency E1 user (ICD 5.1.5): the clock less the
/// group delay of the pair it refers to: BGD(E1,E5b) for I/NAV's (E1,E5b) clock, BGD(E1,E5a)
/// for a data set whose data_sources say its clock is F/NAV's (E1,E5a; bit 8).
double e1_clock_correction_s(const GalileoEphemeris& eph, const GstTime& t);

/// SISA in metres (ICD 5.1.11, Table 89): 0-49: 0-0.49 m by 1 cm, 50-74: 0.5-0.98 m by 2 cm,
/// 75-99: 1-1.96 m by 4 cm, 100-125: 2-6 m by 16 cm; nullopt for the spare indices 126-254 and
/// for 255 (no accuracy prediction available).
std::optional<double> sisa_metres(int index);
/// The index whose value is the smallest one not below `metres` (RINEX stores metres);
/// 255 (NAPA) for negative values (RINEX writes -1) and for anything above 6 m.
int sisa_index_from_metres(double metres);

}  // namespace deepnav::galileo
