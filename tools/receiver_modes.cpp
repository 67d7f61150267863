#include "tools/receiver_modes.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "tools/command_registry.hpp"

namespace deepnav::cli {

const std::vector<ReceiverMode>& receiver_modes() {
  // Scalar tracking is `deepnav run` without a mode option. The aided modes join as
  // e.g. {"ultra", {"--mode", "ultra", "--imu", "{imu}"}}.
  static const std::vector<ReceiverMode> modes = {
      {"scalar", {}},
  };
  return modes;
}

const ReceiverMode& find_receiver_mode(const std::string& name) {
  std::vector<std::string> names;
  for (const auto& m : receiver_modes()) {
    if (m.name == name) return m;
    names.push_back(m.name);
  }
  throw UserError(fmt::format("unknown receiver mode '{}' (available: {})", name, fmt::join(names, ", ")));
}

std::vector<std::string> receiver_mode_run_arguments(const ReceiverMode& mode, const std::string& imu_path) {
  std::vector<std::string> args;
  for (const auto& a : mode.run_arguments) args.push_back(a == "{imu}" ? imu_path : a);
  return args;
}

}  // namespace deepnav::cli
