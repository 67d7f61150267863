#pragma once
// Continuous-time dynamics of the 17 error states (error_state.hpp) about the current
// INS solution, in the local-level NED frame, and their process noise.
//
//   d(dr)/dt  = dv                                     (metres, NED)
//   d(dv)/dt  = -[f_n x] eps + C_b_n dba - (2 w_ie + w_en) x dv + (2 g / R) dr_down e_down
//   d(eps)/dt = -(w_ie + w_en) x eps + C_b_n dbg
//   d(dba)/dt = -dba / tau_a + w_a,   d(dbg)/dt = -dbg / tau_g + w_g   (Gauss-Markov;
//               a random constant with a small random walk when tau = 0)
//   d(b)/dt   = d + w_b,              d(d)/dt = w_d        (receiver clock, metres)
// Terms of the order of the Earth rate times a velocity error (transport-rate errors
// from position errors) are dropped: over the filter's update interval they are far
// below the measurement noise.
//
// Process noise densities come from the IMU grade (velocity/angle random walk, bias
// instability) and the oscillator's Allan-variance coefficients (Brown & Hwang):
// S_b = c^2 h0 / 2, S_d = c^2 2 pi^2 h_-2.
#include "aiding/error_state.hpp"
#include "ins/imu_model.hpp"
#include "ins/strapdown.hpp"

namespace deepnav::aiding {

/// The receiver oscillator the filter assumes: a typical TCXO (Brown & Hwang's figures,
/// h0 = 2e-19, h-2 = 2e-20), louder than the synthesizer's "tcxo" preset (h0 = 2e-21) so
/// that a receiver's real clock is not held too stiff. With the clock steps followed
/// exactly (AidedReceiver), the quieter figure gives the same coupling errors within
/// 0.005 m on paper 003's [docs/references.md] paths.
struct OscillatorNoise {
  double h0 = 2e-19;   ///< white frequency noise coefficient
  double hm2 = 2e-20;  ///< random-walk frequency noise coefficient
};

struct ProcessNoise {
  Eigen::Matrix<double, kStates, 1> psd = Eigen::Matrix<double, kStates, 1>::Zero();  ///< white-noise PSD per state
  double accel_bias_tau_s = 0.0;  ///< 0: random constant (plus the PSD as a random walk)
  double gyro_bias_tau_s = 0.0;
};

/// Process noise from an IMU error model and an oscillator. Bias instability becomes a
/// first-order Gauss-Markov process when the grade gives a correlation time, else a slow
/// random walk that keeps the bias states from freezing.
ProcessNoise process_noise_from(const ImuErrorModel& imu, const OscillatorNoise& oscillator);

/// The dynamics matrix F about `state`, with the specific force f_b (m/s^2, bias-compensated).
StateMatrix error_dynamics(const NavState& state, const Eigen::Vector3d& f_b_mps2, const ProcessNoise& noise);

/// Transition matrix and discrete process noise over dt: Phi = I + F dt + (F dt)^2 / 2,
/// Qd = (Phi Q Phi^T + Q) dt / 2 (trapezoidal).
void discretize(const StateMatrix& F, const ProcessNoise& noise, double dt_s, StateMatrix& Phi, StateMatrix& Qd);

}  // namespace deepnav::aiding
