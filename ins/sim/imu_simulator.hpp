#pragma once
// IMU simulator: the angular rate and specific force an IMU carried along a
// Trajectory would sense (Earth rate, transport rate and normal gravity included),
// integrated exactly over each output interval, then corrupted by an ImuErrorModel.
//
// Model (NED, the frame of the strapdown mechanization in ins/strapdown.hpp):
//   w_ib_b = w_nb_b + C_n_b (w_ie_n + w_en_n)
//   f_b    = C_n_b (dv_n/dt + (2 w_ie_n + w_en_n) x v_n - g_n),  g_n = [0, 0, g(L, h)]
// which is the NED velocity equation dv_n/dt = C_b_n f_b - (2 w_ie_n + w_en_n) x v_n + g_n
// solved for f_b; g is wgs84::normal_gravity_mps2, the same model the mechanization
// uses, so error-free data mechanizes back onto the trajectory.
// An IMU mounted at lever arm l (body axes, from the trajectory's reference point)
// additionally senses dw_ib_b/dt x l + w_ib_b x (w_ib_b x l); its rate is unchanged.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "ins/imu_model.hpp"
#include "ins/imu_sample.hpp"
#include "ins/sim/imu_error_generator.hpp"
#include "ins/trajectory.hpp"

namespace deepnav {

struct ImuSimConfig {
  ImuErrorModel imu;  ///< error figures and the output rate (imu.sample_rate_hz); zeros = ideal IMU
  Eigen::Vector3d lever_arm_b_m = Eigen::Vector3d::Zero();  ///< IMU position from the reference point, body axes
};

/// Error-free rates at one trajectory state.
ImuRates ideal_imu_rates(const TrajectoryState& state, const Eigen::Vector3d& lever_arm_b_m);

/// Error-free increments over [t0_s, t1_s]: the rates integrated by 4-point
/// Gauss-Legendre quadrature (exact for rates that are polynomials of degree 7 in t),
/// so coning and sculling motion inside the interval is represented, not rate x dt.
ImuSample ideal_imu_increment(const Trajectory& trajectory, double t0_s, double t1_s,
                              const Eigen::Vector3d& lever_arm_b_m);

/// Streams samples k = 1, 2, ... at t_k = k / rate (integer counter, no accumulated time)
/// up to the trajectory's end.
class ImuSimulator {
 public:
  /// Throws std::invalid_argument if the rate is not positive. For an open-ended
  /// trajectory sample_count() is 0 and next() never runs out; the caller stops.
  ImuSimulator(const Trajectory& trajectory, const ImuSimConfig& config, std::uint64_t seed);

  /// Number of whole intervals the trajectory covers (0 for open-ended trajectories).
  std::int64_t sample_count() const { return sample_count_; }
  bool done() const { return sample_count_ > 0 && next_index_ > sample_count_; }
  /// The next sample; throws std::out_of_range past the trajectory's end.
  ImuSample next();
  const ImuErrorGenerator& errors() const { return errors_; }
  double sample_rate_hz() const { return rate_hz_; }

 private:
  const Trajectory& trajectory_;
  Eigen::Vector3d lever_arm_b_m_;
  double rate_hz_;
  std::int64_t sample_count_ = 0;
  std::int64_t next_index_ = 1;
  ImuErrorGenerator errors_;
};

/// All samples of a trajectory.
std::vector<ImuSample> simulate_imu(const Trajectory& trajectory, const ImuSimConfig& config, std::uint64_t seed);

}  // namespace deepnav
