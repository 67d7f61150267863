#include "ins/sim/static_imu_sim.hpp"

#include <cmath>
#include <stdexcept>

#include "ins/coarse_alignment.hpp"

namespace deepnav {

std::vector<ImuReading> simulate_static_imu(const Eigen::Matrix3d& C_b_n, double lat_rad, double gravity_mps2,
                                            const StaticImuErrors& errors, double duration_s, double rate_hz,
                                            std::mt19937_64& rng) {
  if (!(duration_s > 0.0) || !(rate_hz > 0.0))
    throw std::invalid_argument("static IMU: duration_s and rate_hz must be positive");
  const StaticImuMean ideal = stationary_imu_outputs(C_b_n, lat_rad, gravity_mps2);
  const auto n = static_cast<std::size_t>(std::llround(duration_s * rate_hz));
  const double accel_sigma = errors.accel_noise_density_mps2_per_rthz * std::sqrt(rate_hz);
  const double gyro_sigma = errors.gyro_noise_density_radps_per_rthz * std::sqrt(rate_hz);
  std::normal_distribution<double> unit(0.0, 1.0);
  auto noise3 = [&]() {
    const double x = unit(rng), y = unit(rng), z = unit(rng);
    return Eigen::Vector3d(x, y, z);
  };
  std::vector<ImuReading> out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    ImuReading r;
    r.t_s = static_cast<double>(k) / rate_hz;
    r.f_b_mps2 = ideal.f_b_mps2 + errors.accel_bias_b_mps2 + accel_sigma * noise3();
    r.w_ib_b_radps = ideal.w_ib_b_radps + errors.gyro_bias_b_radps + gyro_sigma * noise3();
    out.push_back(r);
  }
  return out;
}

}  // namespace deepnav
