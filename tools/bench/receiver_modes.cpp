#include "tools/bench/receiver_modes.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ins/input_error.hpp"

namespace deepnav::bench {
namespace {

ReceiverMode aided(const std::string& name) {
  return {name,
          {"--mode", name, "--imu", "{imu}", "--imu-grade", "{imu_grade}", "--imu-grades-file", "{imu_grades_file}",
           "--imu-lever-arm", "{imu_lever_arm}"},
          true};
}

}  // namespace

const std::vector<ReceiverMode>& receiver_modes() {
  // Scalar tracking is `deepnav run` without a mode option; the INS-aided modes feed the
  // filter with the receiver's PVT (loose), its pseudoranges and rates (tight), or steer
  // the channels from the filter (ultra).
  static const std::vector<ReceiverMode> modes = {
      {"scalar", {}, false},
      aided("loose"),
      aided("tight"),
      aided("ultra"),
  };
  return modes;
}

const ReceiverMode& find_receiver_mode(const std::string& name) {
  std::vector<std::string> names;
  for (const auto& m : receiver_modes()) {
    if (m.name == name) return m;
    names.push_back(m.name);
  }
  throw InputError(fmt::format("unknown receiver mode '{}' (available: {})", name, fmt::join(names, ", ")));
}

std::vector<std::string> receiver_mode_run_arguments(const ReceiverMode& mode, const RunImu& imu) {
  if (mode.needs_imu && imu.path.empty())
    throw InputError(fmt::format("receiver mode '{}' needs an IMU file (--imu), and the run names none", mode.name));
  std::vector<std::string> args;
  for (const auto& a : mode.run_arguments) {
    if (a == "{imu}") args.push_back(imu.path);
    else if (a == "{imu_grade}") args.push_back(imu.grade);
    else if (a == "{imu_grades_file}") args.push_back(imu.grades_file);
    else if (a == "{imu_lever_arm}")
      for (double x : imu.lever_arm_m) args.push_back(fmt::format("{}", x));
    else args.push_back(a);
  }
  return args;
}

}  // namespace deepnav::bench
