#include "ins/sim/simulated_imu_file.hpp"

namespace deepnav {

void write_simulated_imu_csv(const std::string& path, const Trajectory& trajectory, const ImuSimConfig& config,
                             std::uint64_t seed) {
  write_imu_csv(path, simulate_imu(trajectory, config, seed), ImuFileForm::kIncrements, config.imu.sample_rate_hz);
}

}  // namespace deepnav
