#pragma once
// The receiver modes that `deepnav run` offers, in one table: what benchmarks sweep over
// and what they pass to `deepnav run` for each. A new mode is one more row.
#include <string>
#include <vector>

namespace deepnav::cli {

struct ReceiverMode {
  std::string name;
  /// Extra `deepnav run` arguments for this mode; "{imu}" stands for the run's IMU file.
  std::vector<std::string> run_arguments;
};

/// Every mode the receiver offers now.
const std::vector<ReceiverMode>& receiver_modes();
/// The mode of that name; throws UserError "unknown receiver mode 'X' (available: ...)".
const ReceiverMode& find_receiver_mode(const std::string& name);
/// `deepnav run` arguments for a mode, with "{imu}" replaced by imu_path.
std::vector<std::string> receiver_mode_run_arguments(const ReceiverMode& mode, const std::string& imu_path);

}  // namespace deepnav::cli
