// `deepnav sim`: synthesizes the IF file and truth of a scenario.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "signals/if_metadata.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "signals/text_output_file.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/output_folder.hpp"
#include "tools/cli/progress.hpp"
#include "tools/cli/stop_signals.hpp"

namespace deepnav::cli {
namespace {

struct SimOptions {
  std::string scenario_path;
  std::string out_dir;
  unsigned threads = 0;
  double duration_s = -1.0;
  std::string systems;  ///< "gps,galileo": replaces the scenario's systems when set
};

nlohmann::json summary_json(const Scenario& sc, const SynthesisSummary& s) {
  nlohmann::json sats = nlohmann::json::array();
  for (const auto& sat : s.satellites) {
    nlohmann::json entry = {{"prn", sat.prn},
                            {"elevation_deg", sat.elevation_start_deg},
                            {"azimuth_deg", sat.azimuth_start_deg},
                            {"doppler_hz", sat.doppler_start_hz},
                            {"cn0_dbhz", sat.cn0_start_dbhz},
                            {"code_phase_chips", sat.code_phase_start_chips}};
    // The system only where a second one can appear.
    if (!is_gps_only(sc.systems)) entry["id"] = sat.id.to_string();
    sats.push_back(entry);
  }
  return {{"if_file", std::filesystem::path(s.if_path).filename().string()},
          {"metadata_file", std::filesystem::path(s.metadata_path).filename().string()},
          {"format", std::string(to_string(sc.format))},
          {"sample_rate_hz", sc.sample_rate_hz},
          {"if_hz", sc.if_hz},
          {"adc_bits", sc.adc.bits},
          {"start_gps_week", sc.start_time.week},
          {"start_gps_sow", sc.start_time.sow},
          {"duration_s", s.duration_s},
          {"samples", s.samples},
          {"bytes", s.bytes},
          {"truth_file", "truth.csv"},
          {"sat_truth_file", "sat_truth.csv"},
          {"satellites", sats},
          {"wall_s", s.wall_s}};
}

void print_summary(const Scenario& sc, const SynthesisSummary& s) {
  fmt::print("wrote {} ({} samples, {:.3f} s, {} at {:.0f} Hz, IF {:.0f} Hz) in {:.1f} s ({:.1f}x real time)\n",
             s.if_path, s.samples, s.duration_s, to_string(sc.format), sc.sample_rate_hz, sc.if_hz, s.wall_s,
             s.duration_s / std::max(s.wall_s, 1e-9));
  fmt::print("truth: {}  satellites: {}\n", s.truth_path, s.sat_truth_path);
  const bool gps_only = is_gps_only(sc.systems);
  fmt::print("{:>4} {:>8} {:>8} {:>11} {:>9} {:>11}\n", gps_only ? "PRN" : "SAT", "el_deg", "az_deg", "doppler_hz",
             "cn0_dbhz", "code_chips");
  for (const auto& sat : s.satellites) {
    fmt::print("{:>4} {:>8.2f} {:>8.2f} {:>11.2f} {:>9.1f} {:>11.3f}\n",
               gps_only ? std::to_string(sat.prn) : sat.id.to_string(), sat.elevation_start_deg, sat.azimuth_start_deg,
               sat.doppler_start_hz, sat.cn0_start_dbhz, sat.code_phase_start_chips);
  }
}

/// The files `sim` writes into --out for this scenario.
std::vector<std::string> sim_products(const Scenario& sc) {
  const std::string if_file = if_file_name(sc.format);
  return {
      if_file,         metadata_path_for(if_file).string(), "truth.csv", "sat_truth.csv", "scenario.yaml", "imu.csv",
      "synthesis.json"};
}

/// The files `sim` reads, which its products must not replace.
std::vector<NamedInput> sim_inputs(CLI::App& root, const SimOptions& o, const Scenario& sc) {
  std::vector<NamedInput> inputs = config_file_input(root);
  inputs.insert(inputs.end(), {{"--scenario", o.scenario_path},
                               {"the scenario's nav_file", sc.nav_file},
                               {"the scenario's trajectory file", sc.trajectory.csv_path}});
  if (sc.imu.enabled) inputs.push_back({"the scenario's IMU grades file", sc.imu.grades_file});
  return inputs;
}

/// Thrown from the progress callback to end the synthesis after SIGINT, SIGTERM or SIGHUP.
struct Interrupted {};

void run_sim(CLI::App& root, const SimOptions& o) {
  Scenario sc;
  try {
    sc = load_scenario(o.scenario_path, DEEPNAV_SOURCE_DIR);
    if (o.duration_s > 0.0) sc.duration_s = o.duration_s;
    if (!o.systems.empty()) sc.systems = parse_systems_option(o.systems);
    validate_scenario(sc);
  } catch (const UserError&) {
    throw;
  } catch (const std::exception& e) {
    throw UserError(e.what());
  }
  NavData nav;
  try {
    nav = read_rinex_nav(sc.nav_file);
  } catch (const std::exception& e) {
    throw UserError(e.what());
  }
  const OutputFolder out(o.out_dir, sim_products(sc), sim_inputs(root, o, sc));
  IfSynthesizer synth(sc, std::move(nav));
  SynthesisOptions options;
  options.threads = o.threads;
  ProgressLine progress("sim", sc.duration_s);
  StopOnSignals stop_signals;
  options.progress = [&](double fraction) {
    // The synthesizer has no stop of its own: a signal ends it here, between two chunks.
    if (stop_signals.flag().load()) throw Interrupted{};
    progress.update(fraction);
  };
  SynthesisSummary summary;
  try {
    summary = synth.run(out.dir(), options);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  } catch (const Interrupted&) {
    progress.finish();
    const int signal = stop_signals.signal();
    throw UserError(
        fmt::format("interrupted by {}: nothing is written (an incomplete IF file would pass for a short one)",
                    signal_name(signal)),
        interrupted_exit_status(signal));
  }
  progress.finish();
  TextOutputFile json(out.path("synthesis.json"));
  json.write(summary_json(sc, summary).dump(2) + "\n");
  json.commit();
  if (stop_signals.signal() != SIGHUP) print_summary(sc, summary);  // after a hangup the terminal is gone
}

}  // namespace

void add_sim_command(CommandParents& parents) {
  auto opts = std::make_shared<SimOptions>();
  CLI::App* cmd = parents.root.add_subcommand(
      "sim", "Synthesize a GPS L1 C/A (and Galileo E1) IF file and its truth from a scenario");
  cmd->add_option("--scenario", opts->scenario_path, "Scenario file (YAML or JSON; schema in docs/scenarios.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", opts->out_dir, "Output folder (created if missing)")->required();
  cmd->add_option("--threads", opts->threads, "Worker threads for the satellite signals (0: all cores)")
      ->check(CLI::Range(0u, 256u))
      ->capture_default_str();
  cmd->add_option("--duration", opts->duration_s, "Override the scenario's duration (s)")
      ->check(finite_in(1e-3, 86400.0, "seconds"));
  cmd->add_option("--systems", opts->systems,
                  "Override the scenario's systems: gps, galileo or gps,galileo (Galileo needs a navigation file with "
                  "Galileo records)");
  CLI::App* root = &parents.root;
  cmd->callback([opts, root] { run_sim(*root, *opts); });
}

}  // namespace deepnav::cli
