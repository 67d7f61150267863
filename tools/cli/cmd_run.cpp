// `deepnav run`: the receiver on an IF file, with its products in an output folder.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "aiding/navigation_session.hpp"
#include "ins/imu_file.hpp"
#include "ins/imu_model.hpp"
#include "ins/imu_range_check.hpp"
#include "receiver/acquisition/nothing_found.hpp"
#include "receiver/build_date.hpp"
#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/products/file_products.hpp"
#include "receiver/products/run_statistics.hpp"
#include "receiver/products/truth_file.hpp"
#include "receiver/sources/sample_source_factory.hpp"
#include "signals/data_path.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/text_output_file.hpp"
#include "tools/bench/process_usage.hpp"
#include "tools/cli/atmosphere_options.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/long_integration_options.hpp"
#include "tools/cli/output_folder.hpp"
#include "tools/cli/progress.hpp"
#include "tools/cli/snapshot_hints.hpp"
#include "tools/cli/source_options.hpp"
#include "tools/cli/stop_signals.hpp"
#include "tools/cli/summary_file.hpp"
#include "tools/cli/yaml_config.hpp"

namespace deepnav::cli {
using namespace deepnav::bench;  // the engines this command drives
namespace {

struct RunOptions {
  SourceRequest source;
  std::string out_dir, truth_path, assist_nav;
  std::string mitigation = "none";
  std::string systems = "gps";  ///< --systems as given
  ReceiverConfig receiver;
  // INS aiding (--mode loose|tight|ultra).
  std::string assist_ephemeris;
  // Hot start (with --ephemeris-from): coarse-time fixes before any time of week is decoded.
  std::string time_hint, position_hint;
  std::string save_ephemerides;
  std::string mode = "scalar", imu_path, imu_grade = "tactical", imu_grades_file = "data/imu_grades.yaml";
  std::vector<double> imu_lever_arm_m{0.0, 0.0, 0.0};
  bool filter_troposphere = false;
  bool filter_ionosphere = false;
  bool fault_exclusion = true;
  double max_solution_sigma_m = 100.0;
  bool detect_troposphere_mismatch = true;
  bool detect_ionosphere_mismatch = true;
  aiding::LongIntegrationConfig long_integration;
  bool print_config = false;
};

aiding::NavMode parse_mode(const RunOptions& o) {
  const aiding::NavMode mode = aiding::parse_nav_mode(o.mode);
  if (mode != aiding::NavMode::scalar && o.imu_path.empty())
    throw UserError("--mode " + o.mode + " needs an IMU file (--imu FILE)");
  return mode;
}

/// What the run found wrong with its IMU log: gaps (the INS stops across them) and samples
/// beyond the configured grade's measurement range (flagged).
struct ImuIntegrity {
  std::vector<ImuGap> gaps;
  ImuRangeExcess beyond_range;
};

/// Reports the IMU log's gaps and out-of-range samples (with the file) and returns them.
ImuIntegrity check_imu(const RunOptions& o, const ImuLog& imu, const ImuErrorModel& grade) {
  for (const ImuGap& g : imu.gaps)
    spdlog::warn("{}:{}: no IMU data from t = {:.3f} s to {:.3f} s: the INS stops across the gap", o.imu_path, g.line,
                 g.t_before_s, g.t_after_s);
  ImuIntegrity out{imu.gaps, samples_beyond_range(imu.samples, grade)};
  if (out.beyond_range.samples > 0)
    spdlog::warn(
        "{}: {} samples beyond the {} grade's measurement range, the first at t = {:.3f} s ({}): a wrong "
        "--imu-grade, a unit error or a corrupt sample",
        o.imu_path, out.beyond_range.samples, o.imu_grade, *out.beyond_range.first_t_s, out.beyond_range.first_what);
  return out;
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
  c.troposphere.enabled = o.filter_troposphere;
  c.ionosphere.enabled = o.filter_ionosphere;
  c.troposphere.enable_on_mismatch = o.detect_troposphere_mismatch;
  c.ionosphere.enable_on_mismatch = o.detect_ionosphere_mismatch;
  c.fault_exclusion = o.fault_exclusion;
  c.max_published_sigma_m = o.max_solution_sigma_m;
  c.ultra.long_integration = o.long_integration;
  return c;
}

/// The hot start's hints from --time-hint, else the metadata's date of the recording (UTC
/// converted with the navigation file's leap seconds), and --position-hint; none without a time.
std::optional<HotStartHints> hot_start_hints(const RunOptions& o, const SourceSettings& source, const NavData& nav) {
  const std::optional<GpsTime> t = first_sample_time_hint(o.time_hint, source, leap_seconds_of(nav));
  if (!t) return std::nullopt;
  HotStartHints hints;
  hints.first_sample_time = *t;
  if (!o.position_hint.empty()) hints.position_ecef_m = parse_position_hint(o.position_hint);
  return hints;
}

/// The session's configuration from the options (assistance files read here).
aiding::NavigationSessionConfig session_config(const RunOptions& o, const SourceSettings& source,
                                               aiding::NavMode mode) {
  aiding::NavigationSessionConfig c;
  if (mode == aiding::NavMode::scalar) {
    c.navigator.mode = mode;
    c.navigator.receiver = o.receiver;
  } else {
    c.navigator = aided_config(o, mode);
  }
  c.mitigation.mode = parse_mitigation_mode(o.mitigation);
  try {
    // Both assistance options usually name the same file: read it once.
    std::optional<NavData> iono_nav;
    if (!o.assist_nav.empty()) {
      iono_nav = read_rinex_nav(o.assist_nav);
      c.assisted_iono = iono_nav->iono;
    }
    if (!o.assist_ephemeris.empty())
      c.assisted_ephemerides = o.assist_ephemeris == o.assist_nav ? *iono_nav : read_rinex_nav(o.assist_ephemeris);
    if (c.assisted_ephemerides) c.navigator.receiver.hot_start = hot_start_hints(o, source, *c.assisted_ephemerides);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  return c;
}

/// Why a run that ran to its end found nothing: no satellite acquired (with the likely
/// causes: a wrong setting hides them whatever the length), or too little signal for one
/// observation epoch (or for any search); none when it found something, or was stopped or
/// failed (those say so themselves).
std::optional<NothingFound> nothing_found(const RunOptions& o, const OpenedSource& opened,
                                          aiding::NavigationSession& session, const RunStatistics& stats) {
  if (opened.interrupted() || opened.failure() || session.run_error()) return std::nullopt;
  GnssReceiver& receiver = session.receiver();
  const AcquisitionEvidence evidence = receiver.acquisition_evidence();
  const bool searched = evidence.strongest.has_value();
  if (searched && receiver.acquired_satellites().empty())
    return diagnose_no_satellite(evidence, opened.settings, receiver.processed_s());
  if (stats.epochs() == 0)
    return too_short(receiver.processed_s(), 1.0 / o.receiver.observation_rate_hz,
                     fmt::format("one observation epoch at --rate {}", o.receiver.observation_rate_hz));
  return std::nullopt;
}

/// A figure of the summary that may be missing: the number, or null.
nlohmann::json number_or_null(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

/// How the receiver's first fix was obtained: {"method", "ephemerides_complete_s"}, null
/// before any fix.
nlohmann::json first_fix_json(const std::optional<FirstFixOrigin>& origin) {
  if (!origin) return nullptr;
  return {{"method", origin->method}, {"ephemerides_complete_s", number_or_null(origin->ephemerides_complete_s)}};
}

/// What the hot start did: {"attempts", "fixes", "first_fix_s", "first_time_correction_s",
/// "last_refusal"}; null without --time-hint.
nlohmann::json hot_start_json(const std::optional<HotStartReport>& report) {
  if (!report) return nullptr;
  return {
      {"attempts", report->attempts},
      {"fixes", report->fixes},
      {"first_fix_s", number_or_null(report->first_fix_sample_s)},
      {"first_time_correction_s", number_or_null(report->first_correction_s)},
      {"last_refusal", report->last_refusal.empty() ? nlohmann::json(nullptr) : nlohmann::json(report->last_refusal)}};
}

/// "16.0 s (cold; ephemerides of four satellites at 15.1 s)", or "-" without a fix.
std::string first_fix_text(const RunStatistics& stats, const std::optional<FirstFixOrigin>& origin) {
  if (!stats.first_fix_s()) return "-";
  std::string text = fmt::format("{:.1f} s", *stats.first_fix_s());
  if (origin && origin->ephemerides_complete_s)
    text += fmt::format(" ({}; ephemerides of four satellites at {:.1f} s)", origin->method,
                        *origin->ephemerides_complete_s);
  else if (origin) text += fmt::format(" ({})", origin->method);
  return text;
}

nlohmann::json run_summary(const RunOptions& o, const OpenedSource& opened, aiding::NavigationSession& session,
                           const RunStatistics& stats, bool scored, const ImuIntegrity& imu_integrity,
                           const std::optional<NothingFound>& empty_run) {
  GnssReceiver& receiver = session.receiver();
  nlohmann::json summary = {
      {"input", opened.input},
      // What the run processed: a file's length only when it was read to the end (not after
      // Ctrl-C), and a stream's from its first sample (not from sample 0).
      {"duration_s", receiver.processed_s()},
      {"epochs", stats.epochs()},
      {"fixes", stats.fixes()},
      {"time_to_first_fix_s", stats.first_fix_s() ? nlohmann::json(*stats.first_fix_s()) : nlohmann::json(nullptr)},
      {"first_fix", first_fix_json(receiver.first_fix_origin())},
      {"hot_start", hot_start_json(receiver.hot_start_report())},
      {"acquired_prns", receiver.acquired_prns()},

      {"ephemerides", receiver.ephemerides().size()},
      {"ephemerides_decoded", receiver.decoded_ephemerides().size()},
      {"satellites_used", stats.satellites().json()},
      {"pdop", stats.pdop().json()}};
  if (!is_gps_only(receiver.systems())) {
    std::vector<std::string> names;
    for (GnssSystem system : receiver.systems()) names.emplace_back(system_name(system));
    summary["systems"] = names;
    std::vector<std::string> acquired;
    for (const SatelliteId& id : receiver.acquired_satellites()) acquired.push_back(id.to_string());
    summary["acquired_satellites"] = acquired;
    summary["galileo_ephemerides_decoded"] = receiver.decoded_galileo_ephemerides().size();
  }
  if (scored) {
    summary["truth"] = o.truth_path;
    summary["horizontal_error_m"] = stats.horizontal_error_m().json();
    summary["vertical_error_m"] = stats.vertical_error_m().json();
    summary["velocity_error_mps"] = stats.velocity_error_mps().json();
  }
  // Navigation data per satellite: a channel tracked for a whole frame without an
  // ephemeris points at corrupted navigation bits (or a wrong --week / spectrum sense).
  nlohmann::json navigation = nlohmann::json::array();
  for (const NavigationStatus& n : receiver.navigation_status()) {
    navigation.push_back({{"prn", n.prn},
                          {"tracked_s", n.tracked_s},
                          {"subframes_decoded", n.subframes_decoded},
                          {"parity_failures", n.parity_failures},
                          {"ephemeris_decoded", n.ephemeris}});
    if (n.tracked_s > 36.0 && !n.ephemeris)
      spdlog::warn(
          "PRN {:2d}: tracked {:.0f} s but no ephemeris decoded ({} subframes, {} failed parity): corrupted "
          "navigation bits?",
          n.prn, n.tracked_s, n.subframes_decoded, n.parity_failures);
  }
  summary["navigation"] = navigation;
  // Filter-guided searches (ultra-tight): where each untracked satellite was looked for and
  // what came of it.
  nlohmann::json guided = nlohmann::json::array();
  for (const GuidedSearchRecord& g : receiver.guided_searches()) {
    nlohmann::json j = {{"prn", g.prn},
                        {"started_s", g.started_s},
                        {"ended_s", g.ended_s},
                        {"elevation_deg", g.elevation_deg},
                        {"outcome", to_string(g.outcome)}};
    if (g.detection)
      j["detection"] = {{"dwell_s", g.detection->dwell_s},
                        {"cn0_dbhz", g.detection->cn0_dbhz},
                        {"code_offset_chips", g.detection->code_offset_chips},
                        {"doppler_offset_hz", g.detection->doppler_offset_hz}};
    guided.push_back(j);
  }
  summary["guided_searches"] = guided;
  summary["mode"] = o.mode;
  if (const aiding::AidedReceiver* aided = session.aided()) {
    summary["mode_changes"] = aiding::mode_changes_json(aided->mode_changes());
    summary["seconds_in_mode"] = session.seconds_in_mode();
    summary["ins_start"] = aided->ins_start_method();
    summary["filter_restarts"] = aided->filter_restarts();
    nlohmann::json gaps = nlohmann::json::array();
    for (const ImuGap& g : imu_integrity.gaps)
      gaps.push_back({{"from_s", g.t_before_s}, {"to_s", g.t_after_s}, {"line", g.line}});
    summary["imu_gaps"] = gaps;
    summary["imu_samples_beyond_range"] = imu_integrity.beyond_range.samples;
    summary["satellite_exclusions"] = aided->satellite_exclusions();
    summary["withheld_solutions"] = aided->withheld_solutions();
    // When the mismatch was found, by how much, when the filter took the state (from the
    // fit, the height given room to move back) and what it estimates at the end.
    const auto mismatch_json = [&](const aiding::DelayMismatchReport& m, const char* error_key) {
      return nlohmann::json{{"found_at_s", *m.found_at_s},
                            {error_key, m.fitted_error},
                            {"state_from_s", number_or_null(m.state_from_s)},
                            {"height_room_m", number_or_null(m.height_room_m)},
                            {"state_at_end", number_or_null(m.state_estimate)}};
    };
    if (const aiding::DelayMismatchReport m = aided->troposphere_mismatch(); m.found_at_s)
      summary["troposphere_mismatch"] = mismatch_json(m, "zenith_error_m");
    if (const aiding::DelayMismatchReport m = aided->ionosphere_mismatch(); m.found_at_s)
      summary["ionosphere_mismatch"] = mismatch_json(m, "scale_error");
  }
  summary["interrupted"] = opened.interrupted();
  // What failed, if anything: the run itself (the products hold what came before), and
  // each product that could not be written (the others are).
  const std::optional<std::string> stream_failure = opened.failure();
  summary["error"] = session.run_error() ? nlohmann::json(*session.run_error())
                     : stream_failure    ? nlohmann::json(*stream_failure)
                                         : nlohmann::json(nullptr);
  nlohmann::json failed = nlohmann::json::array();
  for (const ProductFailure& f : session.product_failures())
    failed.push_back({{"product", f.product}, {"error", f.error}});
  summary["products_failed"] = failed;
  if (opened.is_stream) summary["stream"] = opened.report();
  if (empty_run) summary["nothing_found"] = empty_run->json();
  // What the run cost: peak memory stays flat with run length (products are written as
  // the run goes), which a long stream can check from here.
  summary["resources"] = {{"peak_rss_mib", peak_rss_mib()}, {"cpu_s", process_cpu_s()}};
  return summary;
}

/// summary.json, written once the run has ended (the figures are the whole run's), last of
/// the products so that it can list those that failed.
class SummarySink : public ProductSink {
 public:
  SummarySink(const std::string& path, std::function<nlohmann::json()> summary)
      : file_(path), summary_(std::move(summary)) {}
  void finish(const NavData&) override { file_.write(summary_()); }
  void abandon() noexcept override { file_.fail(); }
  std::string name() const override { return "summary.json"; }

 private:
  SummaryFile file_;
  std::function<nlohmann::json()> summary_;
};

/// --save-ephemerides: the ephemerides in use at the end (decoded, else given) as a RINEX 3
/// navigation file, for the next run's --ephemeris-from (a hot start).
class SavedEphemeridesSink : public ProductSink {
 public:
  SavedEphemeridesSink(const std::string& path, const GnssReceiver& receiver) : file_(path), receiver_(receiver) {}
  void finish(const NavData&) override {
    NavData nav;
    for (const auto& [prn, eph] : receiver_.ephemerides()) nav.ephemerides.push_back(eph);
    nav.iono = receiver_.iono();
    nav.utc = receiver_.utc();
    std::ostringstream rinex;
    write_rinex3_nav(rinex, nav, "deepnav");
    file_.write(rinex.str());
    file_.commit();
  }
  void abandon() noexcept override { file_.fail(); }
  std::string name() const override { return "--save-ephemerides"; }

 private:
  TextOutputFile file_;
  const GnssReceiver& receiver_;
};

/// --save-ephemerides may replace the navigation files given as assistance (read whole at
/// the start: the saved set is their update) but no other input.
void refuse_saving_over_inputs(const std::string& path, const std::vector<NamedInput>& inputs) {
  for (const NamedInput& input : inputs) {
    if (input.path.empty() || input.option == "--ephemeris-from" || input.option == "--iono-from") continue;
    std::error_code ec;
    if (std::filesystem::equivalent(path, input.path, ec) && !ec)
      throw UserError(fmt::format("--save-ephemerides '{}' would replace the input '{}' ({}): choose another file",
                                  path, input.path, input.option));
  }
}

/// The files `run` reads, which its products must not replace.
std::vector<NamedInput> run_inputs(CLI::App& root, const RunOptions& o, const OpenedSource& opened) {
  std::vector<NamedInput> inputs = config_file_input(root);
  if (!opened.is_stream) inputs.push_back({"--input", opened.input});
  for (const NamedInput& input : std::vector<NamedInput>{{"--metadata", o.source.metadata},
                                                         {"--truth", o.truth_path},
                                                         {"--iono-from", o.assist_nav},
                                                         {"--ephemeris-from", o.assist_ephemeris},
                                                         {"--imu", o.imu_path}})
    inputs.push_back(input);
  return inputs;
}

/// --week names a week near the data: from the first GPS week to 1024 weeks (about 20
/// years) after this program was built.
void check_week_option(int week) {
  const int last = build_time().week + 1024;
  if (week < 1 || week > last)
    throw UserError(
        fmt::format("--week {} is not a GPS week of any recording: expected 1 (1980) to {} (1024 weeks after "
                    "this program's build date)",
                    week, last));
}

/// Without --week, a metadata file's date of the recording names the week near the data.
void take_week_from_metadata(const SourceSettings& source, ReceiverConfig& receiver) {
  if (receiver.reference_week > 0 || !source.start_time_utc) return;
  receiver.reference_week = gps_time_from_calendar(*source.start_time_utc).week;
  receiver.reference_week_origin = "the week of " + source.start_time_origin;
}

void run_receiver(CLI::App& root, RunOptions o) {
  std::optional<TruthFile> truth;
  try {
    if (!o.truth_path.empty()) truth.emplace(o.truth_path);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  // A file or a tcp:// / udp:// stream; Ctrl-C ends the source, so the products are still written.
  StopOnSignals stop_signals;
  o.source.stop = &stop_signals.flag();
  OpenedSource opened = open_sample_source(o.source);
  take_week_from_metadata(opened.settings, o.receiver);
  std::vector<std::string> product_names = file_product_names();
  product_names.push_back("summary.json");
  const OutputFolder out(o.out_dir, product_names, run_inputs(root, o, opened));
  if (!o.save_ephemerides.empty()) refuse_saving_over_inputs(o.save_ephemerides, run_inputs(root, o, opened));

  const aiding::NavMode mode = parse_mode(o);
  std::optional<ImuLog> imu;
  if (mode != aiding::NavMode::scalar) imu = read_imu(o);
  const aiding::NavigationSessionConfig config = session_config(o, opened.settings, mode);
  const ImuIntegrity imu_integrity = imu ? check_imu(o, *imu, config.navigator.imu) : ImuIntegrity{};
  std::vector<std::unique_ptr<ProductSink>> products =
      file_products(o.out_dir, std::filesystem::path(opened.input).filename().string(),
                    1.0 / o.receiver.observation_rate_hz, o.receiver.systems);
  aiding::NavigationSession session(config, *opened.source, std::move(imu), opened.duration_s);
  RunStatistics stats(truth ? &*truth : nullptr);
  std::optional<NothingFound> empty_run;  // decided when the run has ended, before the summary is written
  SummarySink summary(out.path("summary.json"), [&] {
    empty_run = nothing_found(o, opened, session, stats);
    return run_summary(o, opened, session, stats, truth.has_value(), imu_integrity, empty_run);
  });
  std::vector<ProductSink*> sinks{&stats};
  for (const auto& p : products) sinks.push_back(p.get());
  std::optional<SavedEphemeridesSink> saved_ephemerides;
  if (!o.save_ephemerides.empty()) sinks.push_back(&saved_ephemerides.emplace(o.save_ephemerides, session.receiver()));
  sinks.push_back(&summary);

  const double total_s = opened.duration_s.value_or(0.0);
  ProgressLine progress("run", total_s);
  try {
    session.run(sinks, [&](double t) {
      if (total_s > 0.0) progress.update(t / total_s);  // a stream's length is not known
    });
  } catch (const std::exception& e) {
    progress.finish();
    if (session.run_error()) throw UserError(fmt::format("{} (products written up to there)", e.what()));
    throw UserError(e.what());
  }
  progress.finish();
  // After a hangup the terminal is gone: the results stay in the products.
  if (stop_signals.signal() != SIGHUP) {
    fmt::print("{} fixes in {} epochs; first fix at {}; satellites acquired: {}\n", stats.fixes(), stats.epochs(),
               first_fix_text(stats, session.receiver().first_fix_origin()),
               session.receiver().acquired_satellites().size());
    if (truth && !stats.horizontal_error_m().values.empty())
      fmt::print("error vs truth: horizontal RMS {:.2f} m, vertical RMS {:.2f} m, velocity RMS {:.3f} m/s\n",
                 stats.horizontal_error_m().rms(), stats.vertical_error_m().rms(), stats.velocity_error_mps().rms());
  }
  if (const auto failure = opened.failure()) throw UserError(*failure + " (products written up to there)");
  if (opened.interrupted()) {
    const int signal = stop_signals.signal();
    throw UserError(fmt::format("interrupted by {}: the products are written up to sample {} (summary.json: "
                                "\"interrupted\": true)",
                                signal_name(signal), opened.source->next_sample_index()),
                    interrupted_exit_status(signal));
  }
  if (empty_run) throw UserError(fmt::format("{}: {}", opened.input, empty_run->message), kExitNothingFound);
}

}  // namespace

void add_run_command(CommandParents& parents) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* root = &parents.root;
  CLI::App* cmd = parents.root.add_subcommand("run", "Run the receiver on an IF file: PVT and products in --out");
  add_source_options(*cmd, o->source, SourceUse::receiver);
  cmd->add_option("--mitigation", o->mitigation,
                  "Interference mitigation: none, notch, excision, blanking, auto (blanking then excision)")
      ->check(CLI::IsMember(mitigation_mode_names()))
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Output folder")->required();
  cmd->add_option("--truth", o->truth_path, "Synthesizer truth.csv: adds error statistics to summary.json");
  cmd->add_option_function<std::string>(
         "--systems",
         [o](const std::string& text) {
           o->systems = text;
           o->receiver.systems = parse_systems_option(text);
         },
         "Satellite systems to track, comma-separated: gps, galileo (4 Msps or more) or gps,galileo")
      ->default_str("gps");
  cmd->add_option("--galileo-channels", o->receiver.galileo.channels, "Galileo E1 tracking channels")
      ->check(CLI::Range(1, kGalileoMaxSvid).description("1 to 36 (one per Galileo SVID at most)"))
      ->capture_default_str();
  cmd->add_option("--channels", o->receiver.channels, "GPS tracking channels")
      ->check(CLI::Range(1, 32).description("1 to 32 (one per GPS PRN at most)"))
      ->capture_default_str();
  cmd->add_option("--pll-order", o->receiver.pll_order,
                  "Carrier loop order: 2, or 3 for high dynamics (follows Doppler ramps)")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  cmd->add_option("--threads", o->receiver.threads,
                  "Channel worker threads (0: all cores; every mode's products are the same for any count)")
      ->check(CLI::Range(0u, kMaxReceiverThreads))
      ->capture_default_str();
  cmd->add_option("--rate", o->receiver.observation_rate_hz, "Observation/PVT rate (Hz, up to 50)")
      ->check(finite_in(0.01, 50.0, "a rate in Hz"))
      ->capture_default_str();
  cmd->add_option("--doppler-max", o->receiver.acquisition.doppler_max_hz, "Acquisition Doppler half-width (Hz)")
      ->check(finite_in(100.0, 50000.0, "a Doppler in Hz"))
      ->capture_default_str();
  cmd->add_option("--iono-from", o->assist_nav,
                  "RINEX navigation file whose ionosphere parameters are used until the broadcast ones are decoded")
      ->check(CLI::ExistingFile);
  add_atmosphere_options(*cmd, o->receiver.atmosphere);
  cmd->add_option(
         "--ephemeris-from", o->assist_ephemeris,
         "RINEX navigation file whose ephemerides are used until the broadcast ones are decoded (assisted start)")
      ->check(CLI::ExistingFile);
  CLI::Option* time_hint =
      cmd->add_option("--time-hint", o->time_hint,
                      "Hot start: approximate time of the file's first sample, 2022-01-01T00:00:03Z (UTC) or without "
                      "Z (GPS), within +-2 minutes: fixes from code phases (coarse time) before any time of week is "
                      "decoded")
          ->needs(cmd->get_option("--ephemeris-from"));
  cmd->add_option("--position-hint", o->position_hint,
                  "Hot start: approximate position LAT,LON,H (deg, deg, m) within ~100 km (default: from the Dopplers)")
      ->needs(time_hint);
  cmd->add_option("--save-ephemerides", o->save_ephemerides,
                  "Write the ephemerides in use at the end (decoded, else given) as RINEX 3 navigation to FILE, for a "
                  "later run's --ephemeris-from");
  cmd->add_option("--mode", o->mode,
                  "scalar, or INS-aided: loose (PVT), tight (pseudorange/rate), ultra (filter steers the channels)")
      ->check(CLI::IsMember({"scalar", "loose", "tight", "ultra"}))
      ->capture_default_str();
  cmd->add_option("--imu", o->imu_path, "IMU CSV file (increments or rates, see docs/formats.md) for the aided modes")
      ->check(CLI::ExistingFile);
  cmd->add_option("--imu-grade", o->imu_grade, "The IMU's grade in --imu-grades-file (its noise and bias figures)")
      ->capture_default_str();
  cmd->add_option("--imu-grades-file", o->imu_grades_file,
                  "IMU grades YAML file (relative: from here, else the project's data/)")
      ->capture_default_str();
  cmd->add_flag("--filter-troposphere,!--no-filter-troposphere", o->filter_troposphere,
                "Tight/ultra: estimate a zenith troposphere residual (an 18th filter state)");
  cmd->add_flag("--filter-ionosphere,!--no-filter-ionosphere", o->filter_ionosphere,
                "Tight/ultra: estimate the ionosphere model's scale error (a 19th filter state)");
  cmd->add_flag("--troposphere-mismatch,!--no-troposphere-mismatch", o->detect_troposphere_mismatch,
                "Tight/ultra: take the zenith troposphere state when the fixes show the troposphere model wrong by "
                "over 1.5 m at the zenith (a signal without troposphere)")
      ->default_str("true");
  cmd->add_flag("--ionosphere-mismatch,!--no-ionosphere-mismatch", o->detect_ionosphere_mismatch,
                "Tight/ultra: take the ionosphere scale state when the fixes show the signal without most of the "
                "ionosphere model's delay (a signal without ionosphere)")
      ->default_str("true");
  add_long_integration_options(*cmd, o->long_integration);
  cmd->add_flag("--guided-reacquisition,!--no-guided-reacquisition", o->receiver.guided.enabled,
                "Ultra: search the satellites not tracked where the filter predicts them (a narrow window, seconds of "
                "integration) and start their channels steered")
      ->default_str("true");
  cmd->add_option("--max-solution-sigma", o->max_solution_sigma_m,
                  "Aided modes: a solution whose horizontal 1-sigma exceeds this (m) is not published")
      ->check(CLI::Range(0.1, 1e6))
      ->capture_default_str();
  cmd->add_flag("--fault-exclusion,!--no-fault-exclusion", o->fault_exclusion,
                "Tight/ultra: exclude a satellite whose pseudorange innovations disagree with the filter")
      ->default_str("true");  // flags capture no default: --print-config reads this one
  cmd->add_option("--imu-lever-arm", o->imu_lever_arm_m,
                  "IMU position from the antenna, body axes x y z (m), as a scenario's imu.lever_arm_m")
      ->expected(3)
      ->check(finite_in(-100.0, 100.0, "metres"));
  cmd->add_option(
      "--week", o->receiver.reference_week,
      "GPS week near the data: resolves the week number the satellites broadcast modulo 1024, and must "
      "agree with it (default: the week of the --metadata file's date, else the --ephemeris-from file's epoch, "
      "else the build date)");
  add_print_config(*cmd, o->print_config);
  cmd->footer(fmt::format(
      "Exit status: 0 done; {} nothing found: no satellite acquired (the message names the likely cause: --fs, "
      "--if, --format, --inverted-spectrum) or too little signal for one observation epoch, the products written and "
      "summary.json's nothing_found saying why; 1 an error; 130, 143, 129 interrupted by SIGINT, SIGTERM, "
      "SIGHUP (the products valid up to there).",
      kExitNothingFound));
  cmd->callback([o, cmd, root] {
    if (o->print_config) return fmt::print("{}", effective_config(*cmd));
    if (cmd->get_option("--week")->count() > 0) check_week_option(o->receiver.reference_week);
    o->receiver.reference_week_origin = "--week";
    note_given_source_options(*cmd, o->source);
    run_receiver(*root, *o);
  });
}

}  // namespace deepnav::cli
