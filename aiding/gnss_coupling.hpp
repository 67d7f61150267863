#pragma once
// The coupling steps of the aided navigators, one implementation for both: the IF-driven
// receiver (aided_receiver.hpp: `deepnav run --mode loose|tight`) and the recording-driven
// one (recorded_fusion.hpp: `deepnav fuse`). Each navigator gathers its own observables and
// their noise (a scalar channel's Doppler sigma from its loop, a recording's configured
// one) and decides when a step runs; how a fix starts the INS, how a PVT enters the filter
// and how a satellite's pseudorange and Doppler become range rows (predicted where, when
// and with which atmosphere) is here.
//
//   INS start     alignment_fix()     a PVT fix as the INS initializer takes it
//                 start_navigator()   the navigator from the initializer's start
//   loose update  loose_update()      the PVT's position at the epoch, its Doppler velocity
//                                     at the Dopplers' time
//   tight update  tight_rows()        per satellite a pseudorange row and a rate row, the
//                                     rate predicted at the Doppler's own time
//
// Time: the navigator's axis (the IMU's); each measurement states where it lies on it. A
// Doppler need not be of the epoch's instant: the IF receiver's is the mean over its last
// 100 ms of carrier phase, which refers to the middle of that window (about 55 ms before
// the epoch, ChannelObservation::doppler_offset_s). Over a 1 g turn that is 0.5 m/s of
// velocity, so both steps compare a Doppler with the INS at the Doppler's time.
#include <Eigen/Core>
#include <optional>
#include <variant>
#include <vector>

#include "aiding/aided_navigator.hpp"
#include "aiding/broadcast_ephemeris.hpp"
#include "aiding/ins_initializer.hpp"
#include "ins/gps_time.hpp"
#include "receiver/pvt/atmosphere_models.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "receiver/pvt/range_weight.hpp"
#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/iono_utc.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav::aiding {

/// What both navigators couple with, taken from one structure: the filter's settings and
/// the atmosphere its ranges are predicted with.
struct CouplingSettings {
  ImuErrorModel imu;  ///< the IMU's grade: process noise and start limits
  OscillatorNoise oscillator;
  Eigen::Vector3d lever_arm_imu_to_antenna_b_m = Eigen::Vector3d::Zero();
  double gate_sigma = 5.0;  ///< innovation gate of the GNSS updates (0: none)
  /// The atmosphere: the models every predicted range applies, the same the navigator's PVT
  /// solver applies (the IF receiver's ReceiverConfig::atmosphere), and the filter's
  /// residual states of those models (estimated from the start when enabled).
  AtmosphereModels atmosphere;
  TroposphereResidualConfig troposphere;
  IonosphereResidualConfig ionosphere;
  double pvt_position_sigma_scale_m = 2.0;  ///< a PVT fix's position sigma = DOP x this (start, loose)
};

/// The navigation filter's configuration from the coupling settings.
NavigatorConfig navigator_config(const CouplingSettings& settings);

// ---- INS start ----

/// A PVT solution at `t_s` (navigator's axis) as the INS initializer takes it: position
/// sigmas its DOPs times `position_sigma_scale_m`, at least 1 m horizontally, 1.5 m up.
GnssFix alignment_fix(const PvtSolution& pvt, double t_s, double position_sigma_scale_m);

/// The navigator that the initializer's `start` begins, its clock the `fix`'s (the one that
/// completed the start) carried to the start's time plus `clock_step_m`, a re-setting of
/// the receiver clock since the fix. Logs the start at `log_t_s` (the navigator's own time
/// label for the epoch).
AidedNavigator start_navigator(const InsStart& start, const GnssFix& fix, const NavigatorConfig& config,
                               double clock_step_m, double log_t_s);

// ---- Loose update ----

/// One epoch's PVT as the loose update takes it.
struct LooseFix {
  double t_s = 0.0;  ///< the epoch, navigator's axis
  PvtSolution pvt;   ///< a valid fix
  /// Its velocity's time minus t_s: the mean time offset of the Dopplers it was solved from.
  double doppler_offset_s = 0.0;
  Eigen::Vector3d velocity_sigma_ned_mps = Eigen::Vector3d::Constant(0.1);
};

/// The fix's antenna position (sigma from its DOPs times `position_sigma_scale_m`) and its
/// velocity, each against the INS at its own time.
KalmanUpdate loose_update(AidedNavigator& nav, const LooseFix& fix, double position_sigma_scale_m);

// ---- Tight update ----

/// One satellite's observables at an epoch for the tight update. E1 and L1 share the carrier
/// frequency, so a Doppler means the same rate for either system.
struct RangeObservation {
  SatelliteId satellite;
  BroadcastEphemeris ephemeris;
  /// On the GPS clock: a Galileo pseudorange less the Galileo system offset (GalileoClockOffset);
  /// none: a rate row only (a Galileo satellite before the offset is known).
  std::optional<double> pseudorange_m;
  double cn0_dbhz = 0.0;             ///< weighs the pseudorange
  std::optional<double> doppler_hz;  ///< none: a pseudorange row only
  double doppler_offset_s = 0.0;     ///< the Doppler's time minus the epoch's
  double rate_sigma_mps = 0.1;       ///< of the pseudorange rate from the Doppler
  /// Added in quadrature to the pseudorange's sigma: what the system offset taken off it is
  /// not sure of (0 for GPS).
  double offset_sigma_m = 0.0;
};

/// One epoch's observables, in the order the rows are to be made.
struct RangeEpoch {
  double t_s = 0.0;     ///< navigator's axis
  GpsTime t_rx;         ///< the receiver clock's time tag of the epoch
  IonoParameters iono;  ///< for the Klobuchar model (invalid: no ionosphere)
  std::vector<RangeObservation> satellites;
};

/// How a pseudorange row is weighed: scale times the range weight model's sigma at the
/// satellite's elevation and C/N0 (scalar_pseudorange_sigma_m), its model terms shared by
/// rows row_interval_s apart (range_weight.hpp: 1 s and longer take them whole).
struct PseudorangeWeighting {
  RangeErrorModel errors;
  double row_interval_s = 1.0;
  double scale = 1.0;
};

/// The rows of one epoch, in the epoch's order.
struct TightRows {
  std::vector<RangeMeasurement> used;        ///< at or above the elevation mask
  std::vector<RangeMeasurement> below_mask;  ///< predicted (geometry) but not to be used
};

/// Each satellite's pseudorange (and, with a Doppler, rate) row against the navigator's
/// prior: the geometry from the antenna extrapolated to the epoch, the rate's geometry and
/// the INS velocity at the Doppler's time, ranges through `atmosphere` with the epoch's
/// ionosphere parameters.
TightRows tight_rows(const AidedNavigator& nav, const RangeEpoch& epoch, const AtmosphereModels& atmosphere,
                     double elevation_mask_rad, const PseudorangeWeighting& weighting);

}  // namespace deepnav::aiding
