#pragma once
// The receiver modes that `deepnav run` offers, in one table: what benchmarks sweep over
// and what they pass to `deepnav run` for each. A new mode is one more row.
#include <array>
#include <string>
#include <vector>

namespace deepnav::bench {

struct ReceiverMode {
  std::string name;
  /// Extra `deepnav run` arguments for this mode. Placeholders taken from the run's
  /// scenario: "{imu}" (the synthesized IMU file), "{imu_grade}", "{imu_grades_file}" and
  /// "{imu_lever_arm}" (three arguments: the scenario's imu.lever_arm_m x y z).
  std::vector<std::string> run_arguments;
  bool needs_imu = false;  ///< the scenario must have an `imu:` section
};

/// The IMU of a run, as the scenario describes it and the synthesizer wrote it.
struct RunImu {
  std::string path;  ///< imu.csv; empty when the scenario has no `imu:` section
  std::string grade;
  std::string grades_file;
  std::array<double, 3> lever_arm_m{0.0, 0.0, 0.0};
};

/// Every mode the receiver offers now.
const std::vector<ReceiverMode>& receiver_modes();
/// The mode of that name; throws InputError "unknown receiver mode 'X' (available: ...)".
const ReceiverMode& find_receiver_mode(const std::string& name);
/// `deepnav run` arguments for a mode with the placeholders filled in from `imu`; throws
/// InputError when the mode needs an IMU and the run has no IMU file.
std::vector<std::string> receiver_mode_run_arguments(const ReceiverMode& mode, const RunImu& imu);

}  // namespace deepnav::bench
