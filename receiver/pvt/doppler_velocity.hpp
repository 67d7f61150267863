#pragma once
// Velocity and clock drift from carrier Dopplers at a known position and time: what a fix
// without transmit times (a coarse-time fix, receiver/pvt/coarse_time_solver.hpp) lacks to
// be a full PVT solution. Each Doppler gives a pseudorange rate
//   -lambda f_k = lf_k u_k.(v_sat,k - v) + d - d_sat,k + (atmosphere's rate)
// (the model of receiver/pvt/range_model.hpp), linear in the receiver velocity v and the
// clock drift d: a four-unknown least squares, equally weighted (Doppler noise barely
// depends on elevation at the C/N0 a tracking loop holds).
#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/pvt/atmosphere_models.hpp"
#include "signals/ephemeris.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

struct DopplerVelocity {
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  double clock_drift_mps = 0.0;  ///< c * receiver clock drift
  int satellites = 0;
};

/// Velocity from `dopplers_hz` (carrier Doppler by PRN, positive when approaching) for a
/// receiver at `r_ecef_m` at GPS time `t`; satellites without an ephemeris in
/// `ephemerides` are left out. nullopt with fewer than four satellites or a geometry that
/// does not fix the four unknowns.
std::optional<DopplerVelocity> velocity_from_dopplers(const std::map<int, double>& dopplers_hz,
                                                      const std::map<int, Ephemeris>& ephemerides, const GpsTime& t,
                                                      const Eigen::Vector3d& r_ecef_m, const IonoParameters& iono,
                                                      const AtmosphereModels& atmosphere);

}  // namespace deepnav
