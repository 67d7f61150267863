// `deepnav run`: the receiver on an IF file, with its products in an output folder.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ins/frames.hpp"
#include "receiver/file_sample_source.hpp"
#include "receiver/mitigation_sample_source.hpp"
#include "receiver/nmea_writer.hpp"
#include "receiver/rinex_obs_writer.hpp"
#include "receiver/track_writers.hpp"
#include "receiver/scalar_receiver.hpp"
#include "receiver/truth_file.hpp"
#include "signals/data_path.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/text_output_file.hpp"
#include "tools/atmosphere_options.hpp"
#include "tools/command_registry.hpp"
#include "tools/progress.hpp"
#include "tools/sample_source_factory.hpp"
#include "tools/yaml_config.hpp"
#include "aiding/aided_receiver.hpp"
#include "ins/imu_file.hpp"
#include "ins/imu_model.hpp"

namespace deepnav::cli {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

struct RunOptions {
  std::string input, format = "ibyte", out_dir, truth_path, assist_nav;
  double fs_hz = 0.0, if_hz = 0.0, skip_s = 0.0;
  bool inverted = false, raw = false;
  double reconnect_timeout_s = 30.0;
  std::string mitigation = "none";
  ReceiverConfig receiver;
  // INS aiding (--mode loose|tight|ultra).
  std::string assist_ephemeris;
  int pll_order = 2;
  std::string mode = "scalar", imu_path, imu_grade = "tactical", imu_grades_file = "data/imu_grades.yaml";
  std::vector<double> imu_lever_arm_m{0.0, 0.0, 0.0};
  bool filter_troposphere = false;
  bool fault_exclusion = true;
  bool print_config = false;
};

/// Error statistics of one quantity.
struct Stats {
  std::vector<double> v;
  nlohmann::json json() const {
    if (v.empty()) return nullptr;
    std::vector<double> s = v;
    std::sort(s.begin(), s.end());
    double sum2 = 0.0;
    for (double x : s) sum2 += x * x;
    return {{"rms", std::sqrt(sum2 / static_cast<double>(s.size()))},
            {"p95", s[static_cast<std::size_t>(0.95 * static_cast<double>(s.size() - 1))]},
            {"max", s.back()},
            {"count", s.size()}};
  }
};

aiding::NavMode parse_mode(const RunOptions& o) {
  const aiding::NavMode mode = aiding::parse_nav_mode(o.mode);
  if (mode != aiding::NavMode::scalar && o.imu_path.empty())
    throw UserError("--mode " + o.mode + " needs an IMU file (--imu FILE)");
  return mode;
}

ImuLog read_imu(const RunOptions& o) {
  try {
    return read_imu_csv(o.imu_path);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
}

aiding::AidedReceiverConfig aided_config(const RunOptions& o, aiding::NavMode mode) {
  aiding::AidedReceiverConfig c;
  c.mode = mode;
  c.receiver = o.receiver;
  try {
    // The default (data/imu_grades.yaml) is the project's file from any working directory.
    c.imu = load_imu_grade(resolve_path(o.imu_grades_file, ".", DEEPNAV_SOURCE_DIR), o.imu_grade).model;
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  c.lever_arm_imu_to_antenna_b_m = -Eigen::Vector3d(o.imu_lever_arm_m[0], o.imu_lever_arm_m[1], o.imu_lever_arm_m[2]);
  c.ultra.spacing_chips = o.receiver.tracking.spacing_chips;
  c.troposphere.enabled = o.filter_troposphere;
  c.fault_exclusion = o.fault_exclusion;
  return c;
}

/// The aided solution in the receiver's PVT form (DOPs and satellites from the receiver's own).
PvtSolution aided_solution(const aiding::AidedEpoch& a) {
  PvtSolution p = a.receiver.pvt;
  p.valid = true;
  if (a.receiver.t_rx) p.t = *a.receiver.t_rx;
  p.r_ecef_m = a.r_ecef_m;
  p.v_ecef_mps = a.v_ecef_mps;
  p.llh = a.llh;
  p.clock_bias_m = a.clock_bias_m;
  p.clock_drift_mps = a.clock_drift_mps;
  return p;
}

void run_receiver(RunOptions o) {
  std::optional<TruthFile> truth;
  try {
    if (!o.truth_path.empty()) truth.emplace(o.truth_path);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  // A file or a tcp:// / udp:// stream; Ctrl-C ends the source, so the products below are still written.
  StopOnSignals stop_signals;
  OpenedSource opened = open_sample_source({o.input, o.format, o.fs_hz, o.if_hz, o.skip_s, o.inverted, o.raw,
                                            o.reconnect_timeout_s, &stop_signals.flag()});
  const std::unique_ptr<SampleSource>& source = opened.source;
  std::error_code ec;
  std::filesystem::create_directories(o.out_dir, ec);
  if (ec) throw UserError("cannot create output folder '" + o.out_dir + "': " + ec.message());
  const auto path = [&](const char* name) { return (std::filesystem::path(o.out_dir) / name).string(); };

  TextOutputFile pvt_csv(path("pvt.csv"));
  pvt_csv.write(
      "t_s,gps_week,gps_sow,valid,x_ecef_m,y_ecef_m,z_ecef_m,lat_deg,lon_deg,height_m,vn_mps,ve_mps,vd_mps,"
      "clock_bias_m,clock_drift_mps,satellites,gdop,pdop,hdop,vdop,excluded,mode,filter_satellites\n");
  TextOutputFile tracking_csv(path("tracking.csv"));
  tracking_csv.write("first_sample,prn,state,integration_s,i_prompt,q_prompt,i_early,q_early,i_late,q_late,doppler_hz,code_rate_cps,cn0_dbhz\n");

  MitigationConfig mitigation;
  mitigation.mode = parse_mitigation_mode(o.mitigation);
  MitigationSampleSource mitigated(*source, mitigation);  // --mitigation none: samples pass untouched
  o.receiver.pull_in.pll_order = o.receiver.tracking_loops.pll_order = o.pll_order;
  const aiding::NavMode mode = parse_mode(o);
  std::unique_ptr<aiding::AidedReceiver> aided;
  std::unique_ptr<ScalarReceiver> scalar;
  if (mode != aiding::NavMode::scalar) {
    aided = std::make_unique<aiding::AidedReceiver>(aided_config(o, mode), mitigated, read_imu(o), opened.duration_s);
  } else {
    scalar = std::make_unique<ScalarReceiver>(o.receiver, mitigated);
  }
  ScalarReceiver& receiver = aided ? aided->receiver() : *scalar;
  try {
    // Both assistance options usually name the same file: read it once.
    std::optional<NavData> iono_nav;
    if (!o.assist_nav.empty()) {
      iono_nav = read_rinex_nav(o.assist_nav);
      receiver.set_assisted_iono(iono_nav->iono);
    }
    if (!o.assist_ephemeris.empty())
      receiver.set_assisted_ephemerides(o.assist_ephemeris == o.assist_nav ? *iono_nav : read_rinex_nav(o.assist_ephemeris));
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  const double total_s = opened.duration_s.value_or(0.0);
  ProgressLine progress("run", total_s);
  std::optional<double> first_fix_s;
  int fixes = 0, epochs = 0;
  Stats horizontal, vertical, speed_error;
  Stats pdop, sats;
  std::vector<ReceiverEpoch> all_epochs;
  std::vector<PvtSolution> fix_list;
  std::string nmea;
  const auto leap_seconds = [&] { return receiver.utc().valid ? receiver.utc().delta_t_ls : 18; };
  std::map<std::string, double> mode_seconds;
  const double epoch_s = 1.0 / o.receiver.observation_rate_hz;
  const auto on_epoch = [&](const ReceiverEpoch& ep, const aiding::AidedEpoch* a) {
        ++epochs;
        all_epochs.push_back(ep);
        if (a) mode_seconds[aiding::to_string(a->mode)] += epoch_s;
        const PvtSolution p = a && a->valid ? aided_solution(*a) : ep.pvt;
        if (!p.valid) return;
        fix_list.push_back(p);
        std::map<int, double> cn0;
        for (const auto& ob : ep.observations) cn0[ob.prn] = ob.cn0_dbhz;
        nmea += nmea_sentences(p, cn0, leap_seconds());
        ++fixes;
        if (!first_fix_s) first_fix_s = ep.t_s;
        const Eigen::Vector3d v_ned = C_e_n(p.llh.lat_rad, p.llh.lon_rad) * p.v_ecef_mps;
        std::string excluded;
        for (int prn : p.excluded_prns) excluded += (excluded.empty() ? "" : " ") + std::to_string(prn);
        pvt_csv.write(fmt::format("{:.3f},{},{:.6f},1,{:.4f},{:.4f},{:.4f},{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{:.2f},{:.2f},{:.2f},{:.2f},{},{},{}\n",
                                  ep.t_s, p.t.week, p.t.sow, p.r_ecef_m.x(), p.r_ecef_m.y(), p.r_ecef_m.z(),
                                  p.llh.lat_rad * kRadToDeg, p.llh.lon_rad * kRadToDeg, p.llh.height_m, v_ned.x(),
                                  v_ned.y(), v_ned.z(), p.clock_bias_m, p.clock_drift_mps, p.used_prns.size(),
                                  p.dops.gdop, p.dops.pdop, p.dops.hdop, p.dops.vdop, excluded,
                                  a ? aiding::to_string(a->mode) : "scalar",
                                  a ? a->filter_satellites : static_cast<int>(p.used_prns.size())));
        pdop.v.push_back(p.dops.pdop);
        sats.v.push_back(static_cast<double>(p.used_prns.size()));
        if (truth) {
          if (const auto t = truth->at(ep.t_s)) {
            const Eigen::Vector3d d = C_e_n(p.llh.lat_rad, p.llh.lon_rad) * (p.r_ecef_m - t->r_ecef_m);
            horizontal.v.push_back(d.head<2>().norm());
            vertical.v.push_back(std::abs(d.z()));
            speed_error.v.push_back((p.v_ecef_mps - t->v_ecef_mps).norm());
          }
        }
  };
  const auto on_correlation = [&](const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
        tracking_csv.write(fmt::format("{},{},{},{:.3f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.3f},{:.4f},{:.1f}\n",
                                       e.first_sample, e.prn, static_cast<int>(ch.state), e.integration_s,
                                       e.prompt.real(), e.prompt.imag(), e.early.real(), e.early.imag(),
                                       e.late.real(), e.late.imag(), e.carrier_doppler_hz, e.code_rate_cps, ch.cn0_dbhz));
  };
  const auto on_progress = [&](double t) {
    if (total_s > 0.0) progress.update(t / total_s);  // a stream's length is not known
  };
  if (aided) {
    aided->run([&](const aiding::AidedEpoch& a) { on_epoch(a.receiver, &a); }, on_correlation, on_progress);
  } else {
    receiver.run([&](const ReceiverEpoch& ep) { on_epoch(ep, nullptr); }, on_correlation, on_progress);
  }
  progress.finish();

  NavData nav;
  for (const auto& [prn, eph] : receiver.ephemerides()) nav.ephemerides.push_back(eph);
  nav.iono = receiver.iono();
  nav.utc = receiver.utc();
  std::ostringstream rinex;
  write_rinex3_nav(rinex, nav, "deepnav");
  TextOutputFile nav_file(path("nav.rnx"));
  nav_file.write(rinex.str());

  nlohmann::json summary = {{"input", o.input},
                            {"duration_s", opened.duration_s ? total_s : static_cast<double>(source->next_sample_index()) / source->sample_rate_hz()},
                            {"epochs", epochs},
                            {"fixes", fixes},
                            {"time_to_first_fix_s", first_fix_s ? nlohmann::json(*first_fix_s) : nlohmann::json(nullptr)},
                            {"acquired_prns", receiver.acquired_prns()},
                            {"ephemerides", nav.ephemerides.size()},
                            {"satellites_used", sats.json()},
                            {"pdop", pdop.json()}};
  if (truth) {
    summary["truth"] = o.truth_path;
    summary["horizontal_error_m"] = horizontal.json();
    summary["vertical_error_m"] = vertical.json();
    summary["velocity_error_mps"] = speed_error.json();
  }
  // Navigation data per satellite: a channel tracked for a whole frame without an
  // ephemeris points at corrupted navigation bits (or a wrong --week / spectrum sense).
  nlohmann::json navigation = nlohmann::json::array();
  for (const NavigationStatus& n : receiver.navigation_status()) {
    navigation.push_back({{"prn", n.prn}, {"tracked_s", n.tracked_s}, {"subframes_decoded", n.subframes_decoded},
                          {"parity_failures", n.parity_failures}, {"ephemeris_decoded", n.ephemeris}});
    if (n.tracked_s > 36.0 && !n.ephemeris)
      spdlog::warn("PRN {:2d}: tracked {:.0f} s but no ephemeris decoded ({} subframes, {} failed parity): corrupted "
                   "navigation bits?", n.prn, n.tracked_s, n.subframes_decoded, n.parity_failures);
  }
  summary["navigation"] = navigation;
  summary["mode"] = o.mode;
  if (aided) {
    nlohmann::json changes = nlohmann::json::array();
    for (const auto& c : aided->mode_changes())
      changes.push_back({{"t_s", c.t_s}, {"from", aiding::to_string(c.from)}, {"to", aiding::to_string(c.to)}, {"reason", c.reason}});
    summary["mode_changes"] = changes;
    summary["seconds_in_mode"] = mode_seconds;
    summary["ins_start"] = aided->ins_start_method();
    summary["filter_restarts"] = aided->filter_restarts();
    summary["satellite_exclusions"] = aided->satellite_exclusions();
  }
  summary["interrupted"] = opened.interrupted();
  if (opened.is_stream) summary["stream"] = opened.report();
  RinexObsHeader obs_header;
  obs_header.interval_s = 1.0 / o.receiver.observation_rate_hz;
  if (!fix_list.empty()) obs_header.approx_position_ecef_m = fix_list.front().r_ecef_m;
  TextOutputFile obs_file(path("obs.rnx"));
  obs_file.write(rinex3_observation_file(obs_header, all_epochs));
  TextOutputFile nmea_file(path("fixes.nmea"));
  nmea_file.write(nmea);
  TextOutputFile kml_file(path("track.kml"));
  kml_file.write(kml_track(fix_list, std::filesystem::path(o.input).filename().string()));
  TextOutputFile gpx_file(path("track.gpx"));
  gpx_file.write(gpx_track(fix_list, std::filesystem::path(o.input).filename().string(), leap_seconds()));
  TextOutputFile summary_file(path("summary.json"));
  summary_file.write(summary.dump(2) + "\n");
  pvt_csv.commit();
  tracking_csv.commit();
  nav_file.commit();
  obs_file.commit();
  nmea_file.commit();
  kml_file.commit();
  gpx_file.commit();
  summary_file.commit();
  fmt::print("{} fixes in {} epochs; first fix at {} s; satellites acquired: {}\n", fixes, epochs,
             first_fix_s ? fmt::format("{:.1f}", *first_fix_s) : std::string("-"), receiver.acquired_prns().size());
  if (truth && !horizontal.v.empty()) {
    const auto h = horizontal.json(), v = vertical.json(), s = speed_error.json();
    fmt::print("error vs truth: horizontal RMS {:.2f} m, vertical RMS {:.2f} m, velocity RMS {:.3f} m/s\n",
               h["rms"].get<double>(), v["rms"].get<double>(), s["rms"].get<double>());
  }
  if (opened.interrupted()) spdlog::warn("interrupted: products written up to sample {}", source->next_sample_index());
  if (const auto failure = opened.failure()) throw UserError(*failure + " (products written up to there)");
}

const bool registered = register_command([](CommandParents& parents) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = parents.root.add_subcommand("run", "Run the receiver on an IF file: PVT and products in --out");
  cmd->add_option("--input", o->input, "IF sample file, tcp://HOST:PORT, udp://HOST:PORT (subscribe) or udp://@HOST:PORT (listen)")->required();
  cmd->add_option("--format", o->format, "ibyte|cs8, ishort|cs16, gr_complex|cf32, byte|s8")->capture_default_str();
  cmd->add_option("--fs", o->fs_hz, "Sample rate (Hz); a framed stream's header carries it");
  cmd->add_flag("--raw", o->raw, "The stream is bare samples (no deepnav framing): needs --format and --fs");
  cmd->add_option("--reconnect-timeout", o->reconnect_timeout_s, "Seconds a dropped stream is retried (with backoff)")->capture_default_str();
  cmd->add_option("--if", o->if_hz, "Intermediate frequency (Hz)")->capture_default_str();
  cmd->add_option("--skip", o->skip_s, "Seconds skipped at the start")->capture_default_str();
  cmd->add_flag("--inverted-spectrum", o->inverted, "The front end delivers I - jQ");
  cmd->add_option("--mitigation", o->mitigation, "Interference mitigation: none, notch, excision, blanking, auto (blanking then excision)")
      ->check(CLI::IsMember(mitigation_mode_names()))
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Output folder")->required();
  cmd->add_option("--truth", o->truth_path, "Synthesizer truth.csv: adds error statistics to summary.json");
  cmd->add_option("--channels", o->receiver.channels, "Tracking channels")->capture_default_str();
  cmd->add_option("--pll-order", o->pll_order, "Carrier loop order: 2, or 3 for high dynamics (follows Doppler ramps)")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  cmd->add_option("--threads", o->receiver.threads, "Channel worker threads (0: all cores; the aided modes track on one)")
      ->capture_default_str();
  cmd->add_option("--rate", o->receiver.observation_rate_hz, "Observation/PVT rate (Hz, up to 50)")->capture_default_str();
  cmd->add_option("--doppler-max", o->receiver.acquisition.doppler_max_hz, "Acquisition Doppler half-width (Hz)")->capture_default_str();
  cmd->add_option("--iono-from", o->assist_nav,
                  "RINEX navigation file whose ionosphere parameters are used until the broadcast ones are decoded")
      ->check(CLI::ExistingFile);
  add_atmosphere_options(*cmd, o->receiver.atmosphere);
  cmd->add_option("--ephemeris-from", o->assist_ephemeris,
                  "RINEX navigation file whose ephemerides are used until the broadcast ones are decoded (assisted start)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--mode", o->mode, "scalar, or INS-aided: loose (PVT), tight (pseudorange/rate), ultra (filter steers the channels)")
      ->check(CLI::IsMember({"scalar", "loose", "tight", "ultra"}))
      ->capture_default_str();
  cmd->add_option("--imu", o->imu_path, "IMU CSV file (increments or rates, see README) for the aided modes")->check(CLI::ExistingFile);
  cmd->add_option("--imu-grade", o->imu_grade, "The IMU's grade in --imu-grades-file (its noise and bias figures)")->capture_default_str();
  cmd->add_option("--imu-grades-file", o->imu_grades_file, "IMU grades YAML file (relative: from here, else the project's data/)")->capture_default_str();
  cmd->add_flag("--filter-troposphere,!--no-filter-troposphere", o->filter_troposphere,
               "Tight/ultra: estimate a zenith troposphere residual (an 18th filter state)");
  cmd->add_flag("--fault-exclusion,!--no-fault-exclusion", o->fault_exclusion,
                "Tight/ultra: exclude a satellite whose pseudorange innovations disagree with the filter")
      ->default_str("true");  // flags capture no default: --print-config reads this one
  cmd->add_option("--imu-lever-arm", o->imu_lever_arm_m, "IMU position from the antenna, body axes x y z (m), as a scenario's imu.lever_arm_m")
      ->expected(3);
  cmd->add_option("--week", o->receiver.reference_week, "GPS week near the data (resolves the 10-bit week; default: today)");
  add_print_config(*cmd, o->print_config);
  cmd->callback([o, cmd] {
    if (o->print_config) return fmt::print("{}", effective_config(*cmd));
    run_receiver(*o);
  });
});

}  // namespace
}  // namespace deepnav::cli
