#include "tools/bench/aided_scenario_run.hpp"

#include <chrono>

#include "aiding/navigation_session.hpp"
#include "ins/frames.hpp"
#include "ins/imu_file.hpp"
#include "receiver/products/truth_file.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::bench {

FileSampleSourceOptions synthesized_source(const Scenario& sc, const SynthesisSummary& s) {
  FileSampleSourceOptions o;
  o.path = s.if_path;
  o.format = sc.format;
  o.sample_rate_hz = sc.sample_rate_hz;
  o.intermediate_frequency_hz = sc.if_hz;
  return o;
}

namespace {

/// Scores every epoch of a run against the synthesizer's truth.
class TruthScoring : public ProductSink {
 public:
  TruthScoring(const TruthFile& truth, double lost_cn0_dbhz, AidedRunResult& result)
      : truth_(truth), lost_cn0_dbhz_(lost_cn0_dbhz), result_(result) {}

  void on_epoch(const NavigationEpoch& n) override {
    EpochError e;
    e.t_s = n.receiver.t_s;
    const auto mode = aiding::nav_mode_named(n.mode);
    if (!mode) throw std::logic_error("no navigation mode is named '" + std::string(n.mode) + "'");
    e.mode = *mode;
    const bool aided = n.from_filter && e.mode != aiding::NavMode::scalar;
    const PvtSolution& p = aided ? n.solution : n.receiver.pvt;
    e.valid = aided || p.valid;
    if (aided && result_.first_aided_s < 0.0) result_.first_aided_s = e.t_s;
    e.gnss_measurements = n.gnss_measurements;
    const auto t = truth_.at(e.t_s);
    e.valid = e.valid && t.has_value();  // an epoch past the truth's end cannot be scored
    if (e.valid) {
      e.error_ned_m = ned_offset_m(t->r_ecef_m, p.r_ecef_m);
      e.velocity_error_mps = (p.v_ecef_mps - t->v_ecef_mps).norm();
    }
    result_.epochs.push_back(e);
  }

  void on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) override {
    if (ch.cn0_dbhz >= lost_cn0_dbhz_) result_.tracked_s[e.prn] += e.integration_s;
  }

 private:
  const TruthFile& truth_;
  double lost_cn0_dbhz_;
  AidedRunResult& result_;
};

}  // namespace

aiding::NavigationSessionConfig scenario_session_config(const Scenario& sc, aiding::NavMode mode) {
  aiding::NavigationSessionConfig cfg;
  cfg.navigator.mode = mode;
  cfg.navigator.receiver.reference_week = sc.start_time.week;
  const NavData nav_data = read_rinex_nav(sc.nav_file);
  cfg.assisted_iono = nav_data.iono;
  cfg.assisted_ephemerides = nav_data;
  if (mode != aiding::NavMode::scalar) {
    cfg.navigator.imu = load_imu_grade(sc.imu.grades_file, sc.imu.grade).model;
    cfg.navigator.lever_arm_imu_to_antenna_b_m =
        -Eigen::Vector3d(sc.imu.lever_arm_m[0], sc.imu.lever_arm_m[1], sc.imu.lever_arm_m[2]);
  }
  return cfg;
}

std::optional<ImuLog> scenario_imu_log(const SynthesisSummary& s, aiding::NavMode mode) {
  if (mode == aiding::NavMode::scalar) return std::nullopt;
  return read_imu_csv(s.imu_path);
}

AidedRunResult run_aided_scenario(const Scenario& sc, const SynthesisSummary& s, aiding::NavMode mode,
                                  const AidedRunSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  FileSampleSource source(synthesized_source(sc, s));
  aiding::NavigationSessionConfig cfg = scenario_session_config(sc, mode);
  aiding::AidedReceiverConfig& nav = cfg.navigator;
  nav.receiver.pll_order = settings.pll_order;
  nav.receiver.atmosphere = settings.atmosphere;
  nav.troposphere.enabled = settings.filter_troposphere;
  nav.ionosphere.enabled = settings.filter_ionosphere;
  nav.ultra.long_integration = settings.long_integration;
  nav.receiver.systems = settings.systems;
  aiding::NavigationSession session(cfg, source, scenario_imu_log(s, mode), sc.duration_s);
  const TruthFile truth(s.truth_path);
  AidedRunResult result;
  TruthScoring scoring(truth, nav.receiver.tracking.lost_cn0_dbhz, result);
  session.run({&scoring});
  if (const aiding::AidedReceiver* aided = session.aided()) {
    result.mode_changes = aided->mode_changes();
    result.satellite_exclusions = aided->satellite_exclusions();
    result.filter_restarts = aided->filter_restarts();
    result.troposphere_mismatch_s = aided->troposphere_mismatch().found_at_s;
    result.ionosphere_mismatch_s = aided->ionosphere_mismatch().found_at_s;
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace deepnav::bench
