#pragma once
// Every measurement the navigation filter takes, in one place: its rows of H on the error
// states (error_state.hpp) and its noise. Each z is "predicted minus measured" = H dx + v.
//
//   antenna position (loose)     z = r_antenna(INS) - r(PVT), NED     antenna_position_row
//   antenna velocity (loose)     z = v_antenna(INS) - v(PVT), NED     position_velocity_rows
//   zero velocity (at rest)      z = v(INS), NED                      velocity_rows
//   pseudorange (tight, ultra)   z = rho(predicted) - rho              pseudorange_row
//   pseudorange rate             z = rho'(predicted) - rho'            pseudorange_rate_row
//
// The antenna is where GNSS measures, the INS computes the IMU: an antenna position error
// is dr - [(C_b_n l) x] eps for the lever arm l (IMU -> antenna, body axes).
//
// Noise. How far a pseudorange can be trusted from the satellite's elevation and the
// signal's C/N0 is the one RangeErrorModel the PVT weighs with (receiver/pvt/range_weight.hpp);
// what depends on how the channel measured is here: a scalar channel's observables (tight
// coupling), one integration of a steered channel's discriminators (ultra-tight), and a
// PVT fix's position and velocity (loose coupling).
#include <Eigen/Core>
#include <optional>

#include "aiding/error_state.hpp"
#include "receiver/pvt/range_weight.hpp"

namespace deepnav::aiding {

// ---- Rows of H ----

/// The row of the antenna position error along u_ned; lever_ned is the lever arm in NED.
StateRow antenna_position_row(const Eigen::Vector3d& u_ned, const Eigen::Vector3d& lever_ned);
/// A PVT fix: antenna position (rows 0-2, NED) and velocity (rows 3-5, NED).
Eigen::Matrix<double, 6, kStates> position_velocity_rows(const Eigen::Vector3d& lever_ned);
/// The IMU's NED velocity (a zero-velocity update).
Eigen::Matrix<double, 3, kStates> velocity_rows();
/// The columns of the delay states (troposphere, ionosphere) in one row; a state that is
/// off has none.
struct DelayStateColumns {
  std::optional<double> troposphere;
  std::optional<double> ionosphere;
};
/// A pseudorange along the line of sight los_ned (receiver to satellite): the range falls
/// as the antenna moves towards the satellite, the clock bias adds, and with a delay state
/// on, its column: the troposphere's mapping function (per metre of zenith residual), the
/// ionosphere model's delay (per unit of scale error).
StateRow pseudorange_row(const Eigen::Vector3d& los_ned, const Eigen::Vector3d& lever_ned,
                         const DelayStateColumns& delay = {});
/// A pseudorange rate: the velocity along the line of sight, the clock drift and, with a
/// delay state on, its column: the rate of the troposphere's mapping, minus the ionosphere
/// model's rate (the carrier is advanced).
StateRow pseudorange_rate_row(const Eigen::Vector3d& los_ned, const DelayStateColumns& delay = {});

// ---- Noise (1 sigma) ----

/// A PVT fix's position sigma (north, east, down; m) from its DOPs and a range sigma
/// scale_m, floored at 1 m horizontally and 1.5 m vertically.
Eigen::Vector3d pvt_position_sigma_ned_m(double hdop, double vdop, double scale_m);

/// A scalar channel's pseudorange (m), one row every row_interval_s: the range weight
/// model with its model terms shared by the rows of a second.
double scalar_pseudorange_sigma_m(const RangeErrorModel& errors, double elevation_rad, double cn0_dbhz,
                                  double row_interval_s);
/// A scalar channel's pseudorange rate (m/s) from its Doppler, a carrier phase difference
/// over the averaging window (kDopplerWindow_s): each end with the PLL's thermal jitter at
/// its C/N0 (Kaplan & Hegarty: Bn / (C/N0) (1 + 1 / (2 T C/N0)) rad^2, C/N0 floored at
/// 20 dB-Hz), plus a 0.02 m/s floor (the receiver clock's white frequency noise over the
/// window, common to every channel, and what is left of the dynamics).
double scalar_rate_sigma_mps(double cn0_dbhz, double pll_bandwidth_hz, double coherent_s);

/// One integration of a steered channel (ultra-tight): its normalised early-minus-late
/// discriminator's noise at the E-L spacing, plus the range weight model's terms per row.
/// `piece_s`: for an integration of pieces combined in power (non-coherently), each piece's
/// coherent length; 0: one coherent integration over integration_s.
double discriminator_pseudorange_sigma_m(const RangeErrorModel& errors, double elevation_rad, double cn0_dbhz,
                                         double integration_s, double spacing_chips, double piece_s = 0.0);
/// The same for one coherent integration of a steered Galileo E1 channel's pilot
/// (e1_code_sigma_chips; cn0_dbhz of the whole E1 signal), its code sigma at least
/// code_sigma_floor_chips.
double e1_discriminator_pseudorange_sigma_m(const RangeErrorModel& errors, double elevation_rad, double cn0_dbhz,
                                            double integration_s, double spacing_chips,
                                            double code_sigma_floor_chips = 0.0);
/// The rate of one steered integration (m/s): with rate_window_s > 0 a mean frequency
/// from the carrier phase at both ends of that window, otherwise the frequency
/// discriminator across one integration (`pairs` of them averaged); each with its floor.
double discriminator_rate_sigma_mps(double cn0_dbhz, double integration_s, double rate_window_s, int pairs = 1);

/// 1-sigma of the normalised early-minus-late envelope discriminator (chips) for E-L
/// spacing d over t_s, from pieces of coherent length piece_s (Kaplan & Hegarty, noncoherent
/// E-L power with normalisation: the 1/(C/N0 t) term is the averaging, the squaring loss
/// 2/((2-d) C/N0 T_piece) that of each coherent piece). piece_s <= 0: one coherent piece.
double code_sigma_chips(double cn0_dbhz, double t_s, double spacing_chips, double piece_s = 0.0);
/// 1-sigma (chips) of the BOC(1,1) early-late envelope discriminator on the E1 pilot over one
/// coherent integration of t_s at a whole-signal C/N0 of cn0_dbhz: the pilot holds
/// e1_pilot_power_fraction() of the power, and the BOC(1,1) peak's slope (3 against 1)
/// with the noise's correlation over the spacing (1 - 3d against 1 - d) leave a third of
/// the BPSK discriminator's variance at the same spacing.
double e1_code_sigma_chips(double cn0_dbhz, double t_s, double spacing_chips);
/// The E1 pilot's C/N0 from the whole signal's, and back.
double e1_pilot_cn0_dbhz(double cn0_dbhz);
double e1_signal_cn0_dbhz(double pilot_cn0_dbhz);
/// Variance (rad^2) of the Costas phase discriminator over one integration of T.
double phase_variance_rad2(double cn0_dbhz, double t_s);
/// 1-sigma (Hz) of a mean frequency from two phases span_s apart, each with variance
/// phase_var_rad2: the carrier phase at both ends of a window, or the cross/dot
/// discriminator between two adjoining integrations (span T).
double mean_frequency_sigma_hz(double phase_var_rad2, double span_s);

}  // namespace deepnav::aiding
