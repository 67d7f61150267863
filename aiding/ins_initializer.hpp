#pragma once
// Starting the INS from the receiver's own data (never from a truth file):
//  - at rest (GNSS speed below 0.2 m/s and the IMU passes the rest check over the last
//    seconds): paper 000's [docs/references.md] two-step coarse alignment (levelling, then gyrocompassing);
//  - moving: attitude from two vector pairs (TRIAD): the specific force, whose navigation-
//    frame value a_n - g_n comes from the GNSS velocity change over about a second (the
//    IMU's mean over the same interval gives the body-frame value), and the direction of
//    travel, assumed along the body x axis (no sideslip). Level flight or driving gives
//    roll/pitch to a few tenths of a degree and heading to about a degree; the filter
//    refines both.
// The returned uncertainty says how good that start is, and becomes the filter's P0.
#include <deque>
#include <optional>
#include <string>

#include "aiding/aided_navigator.hpp"
#include "ins/imu_model.hpp"

namespace deepnav::aiding {

struct GnssFix {
  double t_s = 0.0;  ///< on the IMU's time axis
  Eigen::Vector3d r_antenna_ecef_m;
  Eigen::Vector3d v_antenna_ecef_mps;
  double clock_bias_m = 0.0, clock_drift_mps = 0.0;
  double horizontal_sigma_m = 3.0, vertical_sigma_m = 5.0;
};

struct InsStart {
  NavState state;  ///< of the IMU, at the last IMU sample the initializer saw
  InitialUncertainty uncertainty;
  std::string method;  ///< "two-step coarse alignment" or "moving: TRIAD"
};

class InsInitializer {
 public:
  InsInitializer(const ImuErrorModel& imu, const Eigen::Vector3d& lever_arm_imu_to_antenna_b_m);
  /// Every IMU sample, in time order (a few seconds are kept).
  void add_imu(const ImuSample& sample);
  /// A GNSS fix; returns the start once one can be made (the fix's time should be at or
  /// just after the last IMU sample).
  std::optional<InsStart> add_fix(const GnssFix& fix);

 private:
  std::optional<InsStart> at_rest(const GnssFix& fix) const;
  std::optional<InsStart> moving(const GnssFix& fix) const;
  InsStart finish(const GnssFix& fix, const Eigen::Matrix3d& C_b_n) const;
  ImuErrorModel imu_;
  Eigen::Vector3d lever_b_m_;
  std::deque<ImuSample> recent_;
  /// The fixes of the last seconds: the moving start differences velocities about a second
  /// apart whatever the fix rate (a 0.25 s difference at 4 Hz is four times noisier).
  std::deque<GnssFix> fixes_;
};

}  // namespace deepnav::aiding
