#pragma once
// The error states of the GNSS/INS filter: paper 003's [docs/references.md] 17, in this order:
//   position error (north, east, down metres), velocity error (NED m/s), attitude
//   (tilt) error (NED rad), residual accelerometer bias (body m/s^2), residual gyro
//   bias (body rad/s), receiver clock bias (m) and drift (m/s);
// and two more, each switched off (no process noise, no measurement column, so it never
// moves and couples to nothing: the filter is paper 003's 17-state filter) unless the
// navigator asks for it: the zenith troposphere delay the receiver's model leaves (m, a
// random walk), which enters every pseudorange through the model's mapping function; and
// the ionosphere model's scale error (dimensionless, a random walk: the signal's delay is
// (1 + s) times the model's), which enters each pseudorange as s times the model's delay
// and each carrier rate as minus s times the model's rate (the carrier is advanced).
// Errors are "estimate minus truth". The tilt error eps is defined by
// C_b_n(estimate) = (I + [eps x]) C_b_n(true). The bias states are what is left after
// the INS's bias compensation; the clock states are errors of the navigator's own clock
// model (bias integrated from drift), fed back the same way.
#include <Eigen/Core>

namespace deepnav::aiding {

inline constexpr int kStates = 19;
inline constexpr int kPos = 0;
inline constexpr int kVel = 3;
inline constexpr int kAtt = 6;
inline constexpr int kAccelBias = 9;
inline constexpr int kGyroBias = 12;
inline constexpr int kClockBias = 15;
inline constexpr int kClockDrift = 16;
inline constexpr int kTropo = 17;
inline constexpr int kIono = 18;

using StateVector = Eigen::Matrix<double, kStates, 1>;
using StateMatrix = Eigen::Matrix<double, kStates, kStates>;
using StateRow = Eigen::Matrix<double, 1, kStates>;

}  // namespace deepnav::aiding
