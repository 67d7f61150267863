#pragma once
// Applies an ImuErrorModel to ideal IMU increments: turn-on bias, scale factor and
// misalignment drawn once from the seed, then per sample the Gauss-Markov bias
// instability, angle/velocity random walk and output quantization.
#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "ins/imu_model.hpp"

namespace deepnav {

class ImuErrorGenerator {
 public:
  /// Draws the per-run errors from a generator seeded with `seed` (same seed, same errors).
  ImuErrorGenerator(const ImuErrorModel& model, std::uint64_t seed);

  /// Corrupts the ideal increments over an interval of dt_s in place.
  void apply(double dt_s, Eigen::Vector3d& dtheta_b_rad, Eigen::Vector3d& dv_b_mps);

  const TriadErrorDraw& gyro_draw() const { return gyro_.draw; }
  const TriadErrorDraw& accel_draw() const { return accel_.draw; }
  /// Bias acting now (fixed part + Gauss-Markov part), rad/s and m/s^2: the truth an
  /// aiding filter's bias estimate is scored against.
  Eigen::Vector3d gyro_bias_radps() const { return gyro_.draw.bias + gyro_.markov; }
  Eigen::Vector3d accel_bias_mps2() const { return accel_.draw.bias + accel_.markov; }

 private:
  struct Triad {
    TriadErrorSpec spec;
    TriadErrorDraw draw;
    Eigen::Matrix3d transfer = Eigen::Matrix3d::Identity();  ///< I + diag(scale) + misalignment
    Eigen::Vector3d markov = Eigen::Vector3d::Zero();
    Eigen::Vector3d quantization_residual = Eigen::Vector3d::Zero();
  };

  void draw_turn_on(Triad& triad);
  void corrupt(Triad& triad, double dt_s, Eigen::Vector3d& increment);
  Eigen::Vector3d gaussian3();

  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Triad gyro_;
  Triad accel_;
};

}  // namespace deepnav
