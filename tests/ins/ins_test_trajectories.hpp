#pragma once
// Small analytic trajectories for the IMU simulator and mechanization tests, each
// exactly consistent with the NED kinematics (no numerical integration inside).
#include <cmath>
#include <string>

#include "ins/rotations.hpp"
#include "ins/trajectory.hpp"
#include "ins/wgs84.hpp"

namespace deepnav::test {

/// Fixed position; attitude given by Euler angles as functions of time.
class FixedPointTrajectory : public Trajectory {
 public:
  FixedPointTrajectory(const wgs84::Llh& llh, double duration_s) : llh_(llh), duration_s_(duration_s) {}
  TrajectoryState at(double t_s) const override {
    TrajectoryState s;
    s.t_s = t_s;
    s.r_ecef_m = wgs84::llh_to_ecef(llh_);
    const EulerKinematics k = attitude(t_s);
    s.q_b_n = quaternion_from_euler(k.angles);
    s.w_nb_b_radps = body_rate_from_euler_rates(k.angles, k.rate_radps);
    s.dw_nb_b_radps2 = body_rate_derivative_from_euler(k);
    return s;
  }
  double duration_s() const override { return duration_s_; }
  std::string description() const override { return "fixed point"; }
  virtual EulerKinematics attitude(double) const {
    EulerKinematics k;
    k.angles = {0.02, -0.01, 0.5};
    return k;
  }
  const wgs84::Llh& llh() const { return llh_; }

 private:
  wgs84::Llh llh_;
  double duration_s_;
};

/// Fixed position, roll and pitch oscillating a quarter period apart: a coning motion
/// of the body axes at frequency f with amplitude a.
class ConingTrajectory : public FixedPointTrajectory {
 public:
  ConingTrajectory(const wgs84::Llh& llh, double duration_s, double amplitude_rad, double frequency_hz)
      : FixedPointTrajectory(llh, duration_s), a_(amplitude_rad), w_(2.0 * M_PI * frequency_hz) {}
  EulerKinematics attitude(double t) const override {
    EulerKinematics k;
    k.angles = {a_ * std::sin(w_ * t), a_ * std::cos(w_ * t), 1.0 + 0.05 * t};
    k.rate_radps = {a_ * w_ * std::cos(w_ * t), -a_ * w_ * std::sin(w_ * t), 0.05};
    k.accel_radps2 = {-a_ * w_ * w_ * std::sin(w_ * t), -a_ * w_ * w_ * std::cos(w_ * t), 0.0};
    return k;
  }

 private:
  double a_, w_;
};

/// Constant speed due east along a parallel at constant height, level, heading east:
/// v_ned is constant and longitude grows linearly, which is exact on the ellipsoid.
class EastRunTrajectory : public Trajectory {
 public:
  EastRunTrajectory(const wgs84::Llh& start, double speed_mps, double duration_s)
      : start_(start), speed_(speed_mps), duration_s_(duration_s) {}
  TrajectoryState at(double t_s) const override {
    const double r_east = wgs84::transverse_radius_m(start_.lat_rad) + start_.height_m;
    const double lon_rate = speed_ / (r_east * std::cos(start_.lat_rad));
    wgs84::Llh llh = start_;
    llh.lon_rad += lon_rate * t_s;
    TrajectoryState s;
    s.t_s = t_s;
    s.r_ecef_m = wgs84::llh_to_ecef(llh);
    s.v_ned_mps = {0.0, speed_, 0.0};
    s.q_b_n = quaternion_from_euler({0.0, 0.0, M_PI / 2});
    return s;
  }
  double duration_s() const override { return duration_s_; }
  std::string description() const override { return "east run"; }

 private:
  wgs84::Llh start_;
  double speed_, duration_s_;
};

}  // namespace deepnav::test
