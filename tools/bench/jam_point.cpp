#include "tools/bench/jam_point.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "aiding/navigation_session.hpp"
#include "ins/input_error.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/child_process.hpp"
#include "tools/bench/jam_judge.hpp"
#include "tools/bench/jam_scoring.hpp"
#include "tools/bench/receiver_modes.hpp"

namespace deepnav::bench {
namespace {

namespace fs = std::filesystem;

/// What the run itself reports beside its products: an aided mode's mode changes and
/// seconds in each mode (null in scalar mode).
struct JamRunRecord {
  nlohmann::json mode_changes = nlohmann::json::array();
  nlohmann::json seconds_in_mode;
};

/// The run `run` describes, in-process, with its products handed to `recorder`.
JamRunRecord run_in_process(const RunConfiguration& run, JamRecorder& recorder) {
  FileSampleSource source(run_source_options(run));
  // As `deepnav run` does: the IMU log must cover the file's length.
  const double duration_s = static_cast<double>(source.total_samples()) / run.sample_rate_hz;
  aiding::NavigationSession session(run_session_config(run), source, run_imu_log(run), duration_s);
  session.run({&recorder});
  JamRunRecord record;
  if (const aiding::AidedReceiver* aided = session.aided()) {
    record.mode_changes = aiding::mode_changes_json(aided->mode_changes());
    record.seconds_in_mode = session.seconds_in_mode();
  }
  return record;
}

void add_verdict(nlohmann::json& fig, const JamVerdict& v) {
  fig["tracked_fraction_mean"] = v.tracked_fraction_mean;
  fig["tracked_fraction_min"] = v.tracked_fraction_min;
  fig["signal_fraction_mean"] = v.signal_fraction_mean;
  fig["cn0_mean_dbhz"] = v.cn0_mean_dbhz ? nlohmann::json(*v.cn0_mean_dbhz) : nlohmann::json(nullptr);
  fig["failed"] = v.failed;
  fig["failure"] = v.failure;
}

}  // namespace

JammerConfig benchmark_jammer(const std::string& type, double js_db, double onset_s) {
  JammerConfig j;
  try {
    j.type = parse_jammer_type(type);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--jammer: ") + e.what());
  }
  j.js_db = js_db;
  j.start_s = onset_s;
  switch (j.type) {
    case JammerType::cw:
      j.center_offset_hz = 151.7e3;  // between C/A spectral lines, inside the main lobe
      break;
    case JammerType::chirp:
      j.bandwidth_hz = 2.0e6;
      j.sweep_period_s = 1e-3;
      break;
    case JammerType::wideband:
      j.bandwidth_hz = 2.046e6;  // the C/A main lobe
      break;
    case JammerType::pulsed:
      j.bandwidth_hz = 2.046e6;
      j.duty_cycle = 0.1;
      j.pulse_rate_hz = 3000.0;
      break;
  }
  return j;
}

std::string point_id(const JamPoint& p) {
  const aiding::LongIntegrationConfig defaults;
  const bool own_integration = p.long_integration.coherent_ms != defaults.coherent_ms ||
                               p.long_integration.noncoherent_ms != defaults.noncoherent_ms;
  std::string systems = systems_list(p.systems);
  std::replace(systems.begin(), systems.end(), ',', '-');
  return fmt::format(
      "{}_{}_js{:05.1f}_{}{}_{}_s{}{}{}", fs::path(p.scenario).stem().string(), p.jammer, p.js_db, p.mode,
      p.long_integration.assist_data_bits ? "-assisted-bits" : "", p.mitigation, p.seed,
      own_integration ? fmt::format("_c{}n{}", p.long_integration.coherent_ms, p.long_integration.noncoherent_ms) : "",
      is_gps_only(p.systems) ? "" : "_" + systems);
}

std::string point_dir(const std::string& out_dir, const JamPoint& p) {
  return (fs::path(out_dir) / "points" / point_id(p)).string();
}

bool point_done(const std::string& out_dir, const JamPoint& p) {
  return fs::exists(fs::path(point_dir(out_dir, p)) / "point.json");
}

Scenario jam_point_scenario(const JamPoint& p) {
  const ReceiverMode& mode = find_receiver_mode(p.mode);
  Scenario sc;
  try {
    sc = load_scenario(p.scenario, DEEPNAV_SOURCE_DIR);
    sc.seed = p.seed;
    if (!(p.onset_s >= 0.0 && p.onset_s < sc.duration_s))
      throw InputError(fmt::format("--onset {} s: expected within the scenario's {} s", p.onset_s, sc.duration_s));
    sc.jammers = {benchmark_jammer(p.jammer, p.js_db, p.onset_s)};
    if (mode.needs_imu && !sc.imu.enabled)
      throw InputError(
          fmt::format("receiver mode '{}' needs an IMU, but scenario '{}' has no imu: section "
                      "(e.g. imu: {{grade: tactical, rate_hz: 100}})",
                      p.mode, p.scenario));
    validate_scenario(sc);
    require_scenario_systems(sc, p.systems, p.scenario);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    throw InputError(e.what());
  }
  return sc;
}

RunConfiguration jam_point_run(const JamPoint& p, const Scenario& sc, const JamPointFiles& files) {
  RunConfiguration run;
  run.input = files.if_path;
  run.format = sc.format;
  run.sample_rate_hz = sc.sample_rate_hz;
  run.if_hz = sc.if_hz;
  run.week = sc.start_time.week;
  run.iono_from = sc.nav_file;
  run.ephemeris_from = sc.nav_file;
  run.truth = files.truth_path;
  run.mitigation = p.mitigation;
  run.coherent_ms = p.long_integration.coherent_ms;
  run.noncoherent_ms = p.long_integration.noncoherent_ms;
  run.assist_data_bits = p.long_integration.assist_data_bits;
  run.mode = p.mode;
  run.imu = {files.imu_path, sc.imu.grade, sc.imu.grades_file, sc.imu.lever_arm_m};
  run.out_dir = files.run_dir;
  run.systems = p.systems;
  return run;
}

nlohmann::json run_jam_point(const JamPoint& p, const std::string& out_dir) {
  const auto start = std::chrono::steady_clock::now();
  const Scenario sc = jam_point_scenario(p);
  const fs::path dir = point_dir(out_dir, p);
  const fs::path work = dir / "work";
  fs::create_directories(work);
  SynthesisOptions so;
  so.threads = 1;
  const SynthesisSummary s = IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run((work / "sim").string(), so);

  // One configuration, run here and recorded as the `deepnav run` that reruns it by hand.
  const RunConfiguration run = jam_point_run(p, sc, {s.if_path, s.truth_path, s.imu_path, (work / "run").string()});
  JamRecorder recorder(run.sample_rate_hz);
  const JamRunRecord record = run_in_process(run, recorder);

  nlohmann::json fig = {{"id", point_id(p)},
                        {"scenario", fs::path(p.scenario).stem().string()},
                        {"jammer", p.jammer},
                        {"js_db", p.js_db},
                        {"mode", p.mode},
                        {"mitigation", p.mitigation},
                        {"seed", p.seed},
                        {"onset_s", p.onset_s},
                        {"duration_s", sc.duration_s},
                        {"adc_bits", sc.adc.bits},
                        {"coherent_ms", p.long_integration.coherent_ms},
                        {"noncoherent_ms", p.long_integration.noncoherent_ms},
                        {"assisted_data_bits", p.long_integration.assist_data_bits},
                        {"command", shell_command_line(run_command(run))}};
  if (!is_gps_only(p.systems)) fig["systems"] = systems_list(p.systems);
  const ChannelTimeline timeline =
      channel_timeline(recorder.tracking, s.sat_truth_path, p.onset_s, sc.duration_s, p.systems);
  const JamChannels channels = channel_figures(timeline, p.onset_s, sc.duration_s);
  const JamSolutionFigures solution =
      solution_figures(recorder.solutions, run.truth, timeline, p.onset_s, sc.duration_s);
  fig["channels"] = to_json(channels);
  fig["solution"] = to_json(solution);
  add_verdict(fig, judge_jam_point(channels, solution));
  fig["mode_changes"] = record.mode_changes;
  if (!record.seconds_in_mode.is_null()) fig["seconds_in_mode"] = record.seconds_in_mode;
  fs::remove_all(work);
  fig["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  TextOutputFile out((dir / "point.json").string());
  out.write(fig.dump(2) + "\n");
  out.commit();
  return fig;
}

std::string jam_point_summary(const nlohmann::json& fig) {
  return fmt::format("{}: tracked {:.2f}, C/N0 {}, fixes {:.2f}, horizontal max {} m -> {}",
                     fig["id"].get<std::string>(), fig["tracked_fraction_mean"].get<double>(),
                     fig["cn0_mean_dbhz"].dump(), fig["solution"]["fix_availability"].get<double>(),
                     fig["solution"]["horizontal_max_m"].dump(),
                     fig["failed"].get<bool>() ? "FAIL (" + fig["failure"].get<std::string>() + ")" : "ok");
}

}  // namespace deepnav::bench
