#pragma once
// The IMU file of a simulated scenario: what `deepnav sim` writes next to the IF data.
#include <cstdint>
#include <string>

#include "ins/imu_file.hpp"
#include "ins/sim/imu_simulator.hpp"
#include "ins/trajectory.hpp"

namespace deepnav {

/// Simulates the IMU along the whole trajectory (seeded, reproducible byte for byte)
/// and writes it as an increment-form CSV via `<path>.partial`, renamed on success.
/// Throws std::invalid_argument for an open-ended trajectory or a bad rate.
void write_simulated_imu_csv(const std::string& path, const Trajectory& trajectory, const ImuSimConfig& config,
                             std::uint64_t seed);

}  // namespace deepnav
