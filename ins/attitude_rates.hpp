#pragma once
// Body rate w.r.t. the navigation frame, and its derivative, from an attitude that is
// known as a smooth function of time: w_nb_b = 2 vec(q* dq/dt) and
// dw_nb_b/dt = 2 vec(q* d2q/dt2) (the scalar part of dq*/dt dq/dt vanishes), with the
// derivatives of q from fourth-order central differences.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>

namespace deepnav {

struct AttitudeRates {
  Eigen::Vector3d w_nb_b_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d dw_nb_b_radps2 = Eigen::Vector3d::Zero();
};

/// q_b_n_of_t must be smooth around t; q_at_t is its value at t. step_s is the
/// difference step (2 ms suits vehicle motion: truncation and round-off both stay
/// below 1e-9 rad/s).
AttitudeRates attitude_rates(const std::function<Eigen::Quaterniond(double)>& q_b_n_of_t, double t,
                             const Eigen::Quaterniond& q_at_t, double step_s = 2e-3);

}  // namespace deepnav
