// `deepnav fuse`: the aided navigator on recordings (RINEX observations and navigation
// data, an IMU log), with the products of `deepnav run` in an output folder.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <csignal>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "aiding/recorded_fusion.hpp"
#include "ins/imu_log_reader.hpp"
#include "receiver/observations/solution_file.hpp"
#include "receiver/products/file_products.hpp"
#include "receiver/products/product_group.hpp"
#include "receiver/products/run_statistics.hpp"
#include "signals/data_path.hpp"
#include "tools/cli/atmosphere_options.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/output_folder.hpp"
#include "tools/cli/stop_signals.hpp"
#include "tools/cli/summary_file.hpp"
#include "tools/cli/yaml_config.hpp"

namespace deepnav::cli {
namespace {

/// Where an IMU or an antenna can be from the body's origin (m): a vehicle's size, not a
/// unit error.
constexpr double kMaxBodyOffset_m = 100.0;
/// The largest IMU time offset (s): beyond GPS seconds since 1970 (1.8e9 now) by far, and
/// small enough that a time of the log keeps its microseconds.
constexpr double kMaxTimeOffset_s = 1e10;

struct FuseOptions {
  std::string obs, nav, imu, out_dir, mode = "tight";
  std::string imu_format = "deepnav", imu_columns = "t,ax,ay,az,gx,gy,gz", imu_quantity = "rates";
  std::string imu_accel_unit = "m/s^2", imu_gyro_unit = "rad/s", imu_time_base = "week-seconds";
  double imu_time_scale = 1.0, imu_time_offset_s = 0.0, imu_rate_hz = 0.0;
  std::vector<double> imu_rpy_deg{0.0, 0.0, 0.0}, imu_position_m{0.0, 0.0, 0.0}, antenna_position_m{0.0, 0.0, 0.0};
  std::string imu_grade = "consumer-mems", imu_grades_file = "data/imu_grades.yaml";
  std::string reference, compare;
  bool zupt = true, smoothing = true;
  double smoothing_window_s = 100.0, doppler_bridge_s = 1.0;
  double pseudorange_sigma_scale = 1.0, doppler_sigma_mps = 0.1;
  double elevation_mask_deg = 5.0;
  AtmosphereModels atmosphere;
  bool print_config = false;
};

/// A relative path the configuration file gave is relative to that file's folder.
void resolve_config_paths(CLI::App& root, FuseOptions& o) {
  const CLI::Option* config = root.get_config_ptr();
  if (config == nullptr || config->results().empty()) return;
  const std::string file = config->results().front();
  YAML::Node y;
  try {
    y = YAML::LoadFile(file);
  } catch (const YAML::Exception&) {
    return;  // the configuration reader has reported it already
  }
  const std::string dir = std::filesystem::path(file).parent_path().string();
  for (auto [key, value] : {std::pair{"obs", &o.obs},
                            {"nav", &o.nav},
                            {"imu", &o.imu},
                            {"reference", &o.reference},
                            {"compare", &o.compare},
                            {"out", &o.out_dir},
                            {"imu-grades-file", &o.imu_grades_file}}) {
    for (const std::string& k : {std::string(key), [&] {
                                   std::string u = key;
                                   std::replace(u.begin(), u.end(), '-', '_');
                                   return u;
                                 }()}) {
      if (y[k] && y[k].IsScalar() && y[k].Scalar() == *value && !value->empty() &&
          !std::filesystem::path(*value).is_absolute())
        *value = (std::filesystem::path(dir.empty() ? "." : dir) / *value).lexically_normal().string();
    }
  }
}

/// The files of `fuse`, in its --out folder.
const std::vector<std::string> kFuseProducts{"pvt.csv", "fixes.nmea", "track.kml",       "track.gpx",   "obs.rnx",
                                             "nav.rnx", "filter.csv", "innovations.csv", "summary.json"};

/// A per-epoch trace of the fusion (filter.csv, innovations.csv): a header, then rows
/// written from the fusion's trace callback.
class TraceCsvSink final : public FileSink {
 public:
  TraceCsvSink(const std::string& path, std::string_view header) : FileSink(path) { file_.write(header); }
  void write(std::string_view rows) { file_.write(rows); }
};

/// Thrown from the trace callback to end the fusion after SIGINT, SIGTERM or SIGHUP.
struct Interrupted {};

void require_file(const std::string& path, const char* option) {
  if (path.empty()) throw UserError(fmt::format("{} FILE is required", option));
  if (!std::filesystem::is_regular_file(path)) throw UserError(fmt::format("{}: no such file '{}'", option, path));
}

/// The satellite records fuse leaves out: those the reader skipped and the Galileo E1 ones it
/// read (fuse navigates with GPS L1 C/A only).
std::map<std::string, int> records_left_out(const ObservationReport& r) {
  std::map<std::string, int> out = r.skipped_satellite_records;
  if (r.galileo_satellite_records > 0) out["E"] += r.galileo_satellite_records;
  return out;
}

/// An observation file without a GPS L1 C/A observable gives fuse nothing to navigate with.
void require_gps(const std::string& path, const ObservationReport& r) {
  if (r.gps_satellite_records > 0) return;
  std::string others;
  for (const auto& [system, records] : records_left_out(r))
    others += fmt::format("{}{} {}", others.empty() ? "" : ", ", system, records);
  throw UserError(fmt::format(
      "--obs {}: no GPS L1 C/A observation in its {} epochs ({}): fuse navigates with GPS L1 C/A only", path, r.epochs,
      others.empty() ? "no other system's either" : "records of other systems skipped: " + others));
}

/// Collects the run's solutions (for the reference statistics).
class SolutionCollector : public ProductSink {
 public:
  void on_epoch(const NavigationEpoch& e) override {
    if (!e.solution.valid || !e.receiver.t_rx) return;
    points_.push_back({*e.receiver.t_rx, e.solution.llh, 0, e.filter_satellites});
  }
  const std::vector<SolutionPoint>& points() const { return points_; }

 private:
  std::vector<SolutionPoint> points_;
};

void run_fuse(CLI::App& root, FuseOptions o) {
  // From the start: a signal while the inputs are read ends the fusion at its first epoch.
  StopOnSignals stop_signals;
  resolve_config_paths(root, o);
  require_file(o.obs, "--obs");
  require_file(o.nav, "--nav");
  require_file(o.imu, "--imu");
  if (o.out_dir.empty()) throw UserError("--out DIR is required");
  if (!o.reference.empty()) require_file(o.reference, "--reference");
  if (!o.compare.empty()) require_file(o.compare, "--compare");

  ObservationFile obs;
  NavData nav;
  ImuLogRead imu;
  ImuLogOptions io;
  aiding::RecordedFusionConfig c;
  std::vector<SolutionPoint> reference, baseline;
  try {
    obs = read_rinex_obs(o.obs);
    nav = read_rinex_nav(o.nav);
    io.format = parse_imu_log_format(o.imu_format);
    io.columns = o.imu_columns;
    if (o.imu_quantity != "rates" && o.imu_quantity != "increments")
      throw std::invalid_argument("--imu-quantity '" + o.imu_quantity + "' is not one of rates, increments");
    io.quantity = o.imu_quantity == "rates" ? ImuQuantity::rates : ImuQuantity::increments;
    io.accel_unit = o.imu_accel_unit;
    io.gyro_unit = o.imu_gyro_unit;
    io.time_scale = o.imu_time_scale;
    io.time_offset_s = o.imu_time_offset_s;
    if (o.imu_rate_hz > 0.0) io.nominal_rate_hz = o.imu_rate_hz;
    const aiding::ImuTimeBase base = aiding::parse_imu_time_base(o.imu_time_base);
    imu = read_imu_log(o.imu, io);
    ImuMounting mounting;
    mounting.rpy_deg = Eigen::Vector3d(o.imu_rpy_deg[0], o.imu_rpy_deg[1], o.imu_rpy_deg[2]);
    mounting.imu_position_b_m = Eigen::Vector3d(o.imu_position_m[0], o.imu_position_m[1], o.imu_position_m[2]);
    mounting.antenna_position_b_m =
        Eigen::Vector3d(o.antenna_position_m[0], o.antenna_position_m[1], o.antenna_position_m[2]);
    apply_mounting(imu.log, mounting);
    aiding::to_fusion_axis(imu.log, base, obs);
    c.mode = aiding::parse_nav_mode(o.mode);
    c.coupling.imu = load_imu_grade(resolve_path(o.imu_grades_file, ".", DEEPNAV_SOURCE_DIR), o.imu_grade).model;
    c.coupling.lever_arm_imu_to_antenna_b_m = mounting.lever_arm_imu_to_antenna_b_m();
    if (!o.reference.empty()) reference = read_rtklib_pos(o.reference);
    if (!o.compare.empty()) baseline = read_rtklib_pos(o.compare);
  } catch (const std::exception& e) {
    throw UserError(e.what());
  }
  for (const std::string& w : obs.report.warnings) spdlog::warn("{}", w);
  for (const std::string& w : imu.report.warnings) spdlog::warn("{}", w);
  require_gps(o.obs, obs.report);
  c.coupling.atmosphere = o.atmosphere;
  c.pvt.elevation_mask_rad = o.elevation_mask_deg * M_PI / 180.0;
  c.pseudorange_sigma_scale = o.pseudorange_sigma_scale;
  c.doppler_sigma_mps = o.doppler_sigma_mps;
  c.carrier_smoothing = o.smoothing && o.smoothing_window_s > 0.0;
  c.smoothing.window_s = o.smoothing_window_s;
  c.smoothing.max_doppler_bridge_s = o.doppler_bridge_s;
  c.stationarity.enabled = o.zupt;

  std::vector<NamedInput> inputs = config_file_input(root);
  inputs.insert(
      inputs.end(),
      {{"--obs", o.obs}, {"--nav", o.nav}, {"--imu", o.imu}, {"--reference", o.reference}, {"--compare", o.compare}});
  const OutputFolder out(o.out_dir, kFuseProducts, inputs);
  const auto path = [&](const char* name) { return out.path(name); };
  std::unique_ptr<aiding::RecordedFusion> fusion;
  try {
    fusion = std::make_unique<aiding::RecordedFusion>(c, obs, nav, imu.log);
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  }
  PvtCsvSink pvt_csv(path("pvt.csv"));
  NmeaSink nmea(path("fixes.nmea"));
  TrackSink track(path("track.kml"), path("track.gpx"), std::filesystem::path(o.obs).filename().string());
  RinexObsSink obs_out(path("obs.rnx"), obs.report.nominal_interval_s > 0 ? obs.report.nominal_interval_s : 1.0);
  RinexNavSink nav_out(path("nav.rnx"));
  TraceCsvSink filter_csv(path("filter.csv"),
                          "t_s,filter,pvt_valid,pvt_satellites,rows,rows_rejected,zero_velocity,clock_jump_m,sigma_n_m,"
                          "sigma_e_m,sigma_d_m\n");
  TraceCsvSink innovations_csv(path("innovations.csv"),
                               "t_s,prn,elevation_deg,cn0_dbhz,smoothing_epochs,code_residual_m,code_normalized,"
                               "code_rejected,rate_residual_mps,rate_rejected\n");
  SummaryFile summary_file(path("summary.json"));
  // Each product on its own: one that fails (a full disk) costs only itself.
  ProductGroup products({&pvt_csv, &nmea, &track, &obs_out, &nav_out, &filter_csv, &innovations_csv});
  RunStatistics stats(nullptr);
  SolutionCollector collected;
  const auto opt = [](const std::optional<double>& v) { return v ? fmt::format("{:.4f}", *v) : std::string(); };
  fusion->set_trace([&](const aiding::FusionEpochTrace& t) {
    // The fusion has no stop of its own: a signal ends it here, at an epoch's start.
    if (stop_signals.flag().load()) throw Interrupted{};
    products.write_for(filter_csv, [&] {
      filter_csv.write(fmt::format("{:.3f},{:d},{:d},{},{},{},{:d},{:.3f},{:.3f},{:.3f},{:.3f}\n", t.t_s, t.filter,
                                   t.pvt_valid, t.pvt_satellites, t.rows, t.rows_rejected, t.zero_velocity,
                                   t.clock_jump_m, t.position_sigma_ned_m.x(), t.position_sigma_ned_m.y(),
                                   t.position_sigma_ned_m.z()));
    });
    products.write_for(innovations_csv, [&] {
      for (const aiding::FusionSatelliteTrace& st : t.satellites)
        innovations_csv.write(fmt::format("{:.3f},{},{:.2f},{:.1f},{},{},{},{:d},{},{:d}\n", t.t_s, st.prn,
                                          st.elevation_deg, st.cn0_dbhz, st.smoothing_epochs, opt(st.code_residual_m),
                                          opt(st.code_normalized), st.code_rejected, opt(st.rate_residual_mps),
                                          st.rate_rejected));
    });
  });
  bool interrupted = false;
  try {
    fusion->run({&stats, &collected, &products});
  } catch (const Interrupted&) {
    interrupted = true;  // the products keep the epochs before the signal
    products.finish(nav);
  }
  if (!interrupted && fusion->report().fixes == 0)
    spdlog::warn("--obs {}: none of its {} epochs gave a fix (do the ephemerides of --nav {} cover them?)", o.obs,
                 fusion->report().epochs, o.nav);

  const ObservationReport& r = obs.report;
  nlohmann::json gaps = nlohmann::json::array(), jumps = nlohmann::json::array(), imu_gaps = nlohmann::json::array();
  for (const auto& g : r.gaps) gaps.push_back({{"line", g.line}, {"seconds", g.seconds}});
  for (const auto& j : r.clock_jumps) jumps.push_back({{"line", j.line}, {"jump_ms", j.jump_ms}});
  for (const auto& g : imu.report.gaps) imu_gaps.push_back({{"line", g.line}, {"seconds", g.t_after_s - g.t_before_s}});
  nlohmann::json summary = {
      {"observations", o.obs},
      {"navigation", o.nav},
      {"imu", o.imu},
      {"mode", o.mode},
      {"epochs", stats.epochs()},
      {"fixes", stats.fixes()},
      {"satellites_used", stats.satellites().json()},
      {"pdop", stats.pdop().json()},
      {"fusion", fusion->report().json()},
      {"observation_file",
       {{"rinex_version", r.version},
        {"time_system", r.time_system},
        {"epochs", r.epochs},
        {"interval_s", r.nominal_interval_s},
        {"header_interval_s", r.header_interval_s ? nlohmann::json(*r.header_interval_s) : nlohmann::json(nullptr)},
        {"repeated_epochs", r.repeated_epochs},
        {"gps_l1_records", r.gps_satellite_records},
        {"skipped_satellite_records", records_left_out(r)},
        {"skipped_gps_values", r.skipped_gps_values},
        {"missing_pseudorange", r.missing_pseudorange},
        {"missing_doppler", r.missing_doppler},
        {"missing_phase", r.missing_phase},
        {"loss_of_lock", r.loss_of_lock},
        {"power_failure_epochs", r.power_failure_epochs},
        {"event_epochs", r.event_epochs},
        {"observation_type_changes", r.observation_type_changes},
        {"cycle_slip_epochs", r.cycle_slip_epochs},
        {"gaps", gaps},
        {"clock_jumps", jumps},
        {"warnings", r.warnings}}},
      {"navigation_file", {{"gps_ephemerides", nav.ephemerides.size()}, {"iono_valid", nav.iono.valid}}},
      {"imu_log",
       {{"format", imu.report.format},
        {"lines", imu.report.lines},
        {"rows", imu.report.rows},
        {"samples", imu.report.samples},
        {"duplicate_rows", imu.report.duplicate_rows},
        {"repeated_time", imu.report.repeated_time},
        {"repeated_values", imu.report.repeated_values},
        {"truncated_lines", imu.report.truncated_lines},
        {"interval_s",
         {{"nominal", imu.report.nominal_interval_s},
          {"min", imu.report.min_interval_s},
          {"max", imu.report.max_interval_s}}},
        {"time_scale", imu.report.time_scale},
        {"time_offset_s", imu.report.time_offset_s},
        {"time_base", o.imu_time_base},
        {"gaps", imu_gaps},
        {"warnings", imu.report.warnings}}},
      {"interrupted", interrupted}};
  nlohmann::json failed = nlohmann::json::array();
  for (const ProductFailure& f : products.failures()) failed.push_back({{"product", f.product}, {"error", f.error}});
  summary["products_failed"] = failed;
  if (!reference.empty()) {
    const ReferenceErrors ours = reference_errors(collected.points(), reference);
    summary["reference"] = o.reference;
    summary["reference_errors"] = ours.json();
    if (ours.epochs == 0)
      fmt::print("against the reference: no epoch scored (no solution within 10 ms of a reference epoch)\n");
    else
      fmt::print(
          "against the reference ({} epochs): mean offset E {:.2f} N {:.2f} U {:.2f} m; horizontal RMS {:.2f} m, "
          "about the mean offset {:.2f} m (max {:.2f} m, 3-D max {:.2f} m)\n",
          ours.epochs, ours.mean_offset_enu_m.x(), ours.mean_offset_enu_m.y(), ours.mean_offset_enu_m.z(),
          ours.rms_horizontal_m, ours.scatter_rms_horizontal_m, ours.scatter_max_horizontal_m, ours.scatter_max_3d_m);
    if (!baseline.empty()) {
      // The baseline on the epochs this run has a solution at.
      std::vector<SolutionPoint> same;
      for (const SolutionPoint& b : baseline)
        for (const GpsTime& t : ours.matched)
          if (std::abs(t.seconds_since(b.t)) <= 0.01) {
            same.push_back(b);
            break;
          }
      const ReferenceErrors base = reference_errors(same, reference);
      summary["compare"] = o.compare;
      summary["compare_errors"] = base.json();
      const std::string baseline_name = std::filesystem::path(o.compare).filename().string();
      if (base.epochs == 0)
        fmt::print("baseline {}: no epoch scored (none on the epochs of this run's solutions)\n", baseline_name);
      else
        fmt::print(
            "baseline {} on the same epochs ({}): horizontal RMS {:.2f} m, about the mean offset {:.2f} m (max "
            "{:.2f} m)\n",
            baseline_name, base.epochs, base.rms_horizontal_m, base.scatter_rms_horizontal_m,
            base.scatter_max_horizontal_m);
    }
  }
  try {
    summary_file.write(summary);
  } catch (const std::runtime_error& e) {
    summary_file.fail();
    throw UserError(products.failures().empty() ? e.what() : products.failure_message() + "; " + e.what());
  }
  if (stop_signals.signal() != SIGHUP)  // after a hangup the terminal is gone
    fmt::print("{} epochs, {} with the {} filter; INS start: {}; {} zero-velocity updates\n", stats.epochs(),
               fusion->report().filter_epochs, o.mode,
               fusion->report().ins_start.empty() ? "none" : fusion->report().ins_start,
               fusion->report().zero_velocity_updates);
  if (!products.failures().empty()) throw UserError(products.failure_message());
  if (interrupted)
    throw UserError(fmt::format("interrupted by {}: the products hold the epochs before it (summary.json: "
                                "\"interrupted\": true)",
                                signal_name(stop_signals.signal())),
                    interrupted_exit_status(stop_signals.signal()));
}

}  // namespace

void add_fuse_command(CommandParents& parents) {
  auto o = std::make_shared<FuseOptions>();
  CLI::App* root = &parents.root;
  CLI::App* cmd = parents.root.add_subcommand(
      "fuse", "Aided navigation from recordings: RINEX observations + navigation data + an IMU log; products in --out");
  cmd->add_option("--obs", o->obs, "RINEX observation file (2.11 or 3.0x; GPS L1 C/A used)");
  cmd->add_option("--nav", o->nav, "RINEX navigation file (GPS ephemerides)");
  cmd->add_option("--imu", o->imu, "IMU log (see --imu-format)");
  cmd->add_option("--mode", o->mode, "loose (PVT into the filter) or tight (pseudorange and Doppler rows)")
      ->check(CLI::IsMember({"loose", "tight"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Output folder");
  cmd->add_option("--imu-format", o->imu_format, "deepnav (our CSV), csv (generic, see --imu-columns) or kf-gins")
      ->check(CLI::IsMember({"deepnav", "csv", "kf-gins"}))
      ->capture_default_str();
  cmd->add_option("--imu-columns", o->imu_columns, "csv: what each column is: t, ax, ay, az, gx, gy, gz or - (ignored)")
      ->capture_default_str();
  cmd->add_option("--imu-quantity", o->imu_quantity, "csv: rates or increments")
      ->check(CLI::IsMember({"rates", "increments"}))
      ->capture_default_str();
  cmd->add_option("--imu-accel-unit", o->imu_accel_unit, "csv accelerometer unit: g or m/s^2 (increments: g*s or m/s)")
      ->capture_default_str();
  cmd->add_option("--imu-gyro-unit", o->imu_gyro_unit, "csv gyro unit: deg/s or rad/s (increments: deg or rad)")
      ->capture_default_str();
  cmd->add_option("--imu-time-base", o->imu_time_base,
                  "What the IMU time (offset + scale x time column) counts: week-seconds (GPS seconds of week), gps "
                  "(GPS seconds since 1980-01-06) or unix-gps (GPS-scale seconds since 1970)")
      ->check(CLI::IsMember({"week-seconds", "gps", "unix-gps"}))
      ->capture_default_str();
  cmd->add_option("--imu-time-scale", o->imu_time_scale, "Seconds per unit of the IMU time column")
      ->check(finite_above(0.0, 1e6, "seconds per unit"))
      ->capture_default_str();
  cmd->add_option("--imu-time-offset", o->imu_time_offset_s,
                  "Seconds added to the scaled IMU time: the time base's origin and any constant IMU-to-GNSS offset")
      ->check(finite_in(-kMaxTimeOffset_s, kMaxTimeOffset_s, "seconds"))
      ->capture_default_str();
  cmd->add_option("--imu-rate", o->imu_rate_hz, "Nominal IMU rate (Hz; 0: the log's mean rate)")
      ->check(finite_in(0.0, 1e5, "a rate in Hz"))
      ->capture_default_str();
  cmd->add_option("--imu-mounting", o->imu_rpy_deg, "Body-to-IMU rotation roll pitch yaw (deg)")
      ->expected(3)
      ->check(finite_in(-360.0, 360.0, "an angle in degrees"));
  cmd->add_option("--imu-position", o->imu_position_m, "IMU position from the body origin, body axes x y z (m)")
      ->expected(3)
      ->check(finite_in(-kMaxBodyOffset_m, kMaxBodyOffset_m, "metres"));
  cmd->add_option("--antenna-position", o->antenna_position_m,
                  "Antenna position from the body origin, body axes x y z (m)")
      ->expected(3)
      ->check(finite_in(-kMaxBodyOffset_m, kMaxBodyOffset_m, "metres"));
  cmd->add_option("--imu-grade", o->imu_grade, "The IMU's grade in --imu-grades-file")->capture_default_str();
  cmd->add_option("--imu-grades-file", o->imu_grades_file,
                  "IMU grades YAML file (relative: from here, else the project's data/)")
      ->capture_default_str();
  cmd->add_flag("--zupt,!--no-zupt", o->zupt, "Zero-velocity updates when the IMU is still")->default_str("true");
  cmd->add_option("--pseudorange-sigma-scale", o->pseudorange_sigma_scale,
                  "tight: pseudorange sigma x this (the shared elevation and C/N0 model)")
      ->check(finite_in(0.01, 100.0, "a scale"))
      ->capture_default_str();
  cmd->add_option(
         "--doppler-sigma", o->doppler_sigma_mps,
         "Sigma of a pseudorange rate from a Doppler (m/s): tight rows; loose: the PVT velocity's, times its DOP")
      ->check(finite_in(0.001, 100.0, "a sigma in m/s"))
      ->capture_default_str();
  cmd->add_flag("--smoothing,!--no-smoothing", o->smoothing, "Carrier smoothing (Hatch filter) of the pseudoranges")
      ->default_str("true");
  cmd->add_option("--smoothing-window", o->smoothing_window_s,
                  "Carrier smoothing window (s; restarts on loss of lock, slips, gaps; 0: none)")
      ->check(finite_in(0.0, 3600.0, "seconds"))
      ->capture_default_str();
  cmd->add_option("--doppler-bridge", o->doppler_bridge_s,
                  "Carrier smoothing: longest phase break carried by the Dopplers instead of a restart (s; 0: none)")
      ->check(finite_in(0.0, 60.0, "seconds"))
      ->capture_default_str();
  cmd->add_option("--elevation-mask", o->elevation_mask_deg, "Elevation mask (deg)")
      ->check(finite_in(-10.0, 90.0, "an elevation in degrees"))
      ->capture_default_str();
  add_atmosphere_options(*cmd, o->atmosphere);
  cmd->add_option("--reference", o->reference, "RTKLIB .pos reference: error statistics in summary.json");
  cmd->add_option("--compare", o->compare, "RTKLIB .pos baseline scored against --reference on the same epochs");
  add_print_config(*cmd, o->print_config);
  cmd->callback([o, cmd, root] {
    if (o->print_config) return fmt::print("{}", effective_config(*cmd));
    run_fuse(*root, *o);
  });
}

}  // namespace deepnav::cli
