#include "tools/bench/run_configuration.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "ins/imu_model.hpp"
#include "ins/input_error.hpp"
#include "receiver/mitigation/mitigation_config.hpp"
#include "signals/data_path.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::bench {

std::vector<std::string> run_command(const RunConfiguration& run) {
  std::vector<std::string> argv = {"deepnav",  "run",
                                   "--input",  run.input,
                                   "--format", to_string(run.format),
                                   "--fs",     fmt::format("{}", run.sample_rate_hz),
                                   "--if",     fmt::format("{}", run.if_hz)};
  const auto add = [&argv](const char* option, const std::string& value) {
    if (value.empty()) return;  // not given: `deepnav run`'s default
    argv.push_back(option);
    argv.push_back(value);
  };
  if (run.week > 0) add("--week", std::to_string(run.week));
  add("--iono-from", run.iono_from);
  add("--ephemeris-from", run.ephemeris_from);
  add("--truth", run.truth);
  add("--mitigation", run.mitigation);
  add("--coherent-ms", std::to_string(run.coherent_ms));
  add("--noncoherent-ms", std::to_string(run.noncoherent_ms));
  add("--out", run.out_dir);
  if (!is_gps_only(run.systems)) add("--systems", systems_list(run.systems));
  if (run.assist_data_bits) argv.push_back("--assist-data-bits");
  for (const auto& a : receiver_mode_run_arguments(find_receiver_mode(run.mode), run.imu)) argv.push_back(a);
  return argv;
}

FileSampleSourceOptions run_source_options(const RunConfiguration& run) {
  FileSampleSourceOptions o;
  o.path = run.input;
  o.format = run.format;
  o.sample_rate_hz = run.sample_rate_hz;
  o.intermediate_frequency_hz = run.if_hz;
  return o;
}

aiding::NavigationSessionConfig run_session_config(const RunConfiguration& run) {
  aiding::NavigationSessionConfig c;
  aiding::AidedReceiverConfig& nav = c.navigator;
  nav.mode = aiding::parse_nav_mode(run.mode);
  nav.receiver.reference_week = run.week;
  nav.receiver.systems = run.systems;
  try {
    if (nav.mode != aiding::NavMode::scalar) {
      // Relative grades files as `deepnav run` finds them: from here, else the project's.
      nav.imu = load_imu_grade(resolve_path(run.imu.grades_file, ".", DEEPNAV_SOURCE_DIR), run.imu.grade).model;
      nav.lever_arm_imu_to_antenna_b_m =
          -Eigen::Vector3d(run.imu.lever_arm_m[0], run.imu.lever_arm_m[1], run.imu.lever_arm_m[2]);
      nav.ultra.long_integration.coherent_ms = run.coherent_ms;
      nav.ultra.long_integration.noncoherent_ms = run.noncoherent_ms;
      nav.ultra.long_integration.assist_data_bits = run.assist_data_bits;
    }
    // Both assistance options usually name the same file: read it once.
    std::optional<NavData> iono_nav;
    if (!run.iono_from.empty()) {
      iono_nav = read_rinex_nav(run.iono_from);
      c.assisted_iono = iono_nav->iono;
    }
    if (!run.ephemeris_from.empty())
      c.assisted_ephemerides = run.ephemeris_from == run.iono_from ? *iono_nav : read_rinex_nav(run.ephemeris_from);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  c.mitigation.mode = parse_mitigation_mode(run.mitigation);
  return c;
}

std::optional<ImuLog> run_imu_log(const RunConfiguration& run) {
  if (aiding::parse_nav_mode(run.mode) == aiding::NavMode::scalar) return std::nullopt;
  try {
    return read_imu_csv(run.imu.path);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

}  // namespace deepnav::bench
