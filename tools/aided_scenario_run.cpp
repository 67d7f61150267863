#include "tools/aided_scenario_run.hpp"

#include <chrono>

#include "ins/frames.hpp"
#include "ins/imu_file.hpp"
#include "receiver/file_sample_source.hpp"
#include "receiver/truth_file.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::cli {

FileSampleSourceOptions synthesized_source(const Scenario& sc, const SynthesisSummary& s) {
  FileSampleSourceOptions o;
  o.path = s.if_path;
  o.format = sc.format;
  o.sample_rate_hz = sc.sample_rate_hz;
  o.intermediate_frequency_hz = sc.if_hz;
  return o;
}

AidedRunResult run_aided_scenario(const Scenario& sc, const SynthesisSummary& s, aiding::NavMode mode,
                                  const AidedRunSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  FileSampleSource source(synthesized_source(sc, s));
  aiding::AidedReceiverConfig cfg;
  cfg.mode = mode;
  cfg.receiver.reference_week = sc.start_time.week;
  cfg.receiver.pull_in.pll_order = settings.pll_order;
  cfg.receiver.tracking_loops.pll_order = settings.pll_order;
  cfg.receiver.atmosphere = settings.atmosphere;
  cfg.troposphere.enabled = settings.filter_troposphere;
  cfg.imu = load_imu_grade(sc.imu.grades_file, sc.imu.grade).model;
  cfg.lever_arm_imu_to_antenna_b_m = -Eigen::Vector3d(sc.imu.lever_arm_m[0], sc.imu.lever_arm_m[1], sc.imu.lever_arm_m[2]);
  aiding::AidedReceiver rx(cfg, source, read_imu_csv(s.imu_path), sc.duration_s);
  const NavData nav = read_rinex_nav(sc.nav_file);
  rx.receiver().set_assisted_iono(nav.iono);
  rx.receiver().set_assisted_ephemerides(nav);
  const TruthFile truth(s.truth_path);
  AidedRunResult result;
  const double lost_dbhz = cfg.receiver.tracking.lost_cn0_dbhz;
  rx.run(
      [&](const aiding::AidedEpoch& a) {
        EpochError e;
        e.t_s = a.receiver.t_s;
        e.mode = a.mode;
        const bool aided = a.valid && a.mode != aiding::NavMode::scalar;
        const Eigen::Vector3d r = aided ? a.r_ecef_m : a.receiver.pvt.r_ecef_m;
        const Eigen::Vector3d v = aided ? a.v_ecef_mps : a.receiver.pvt.v_ecef_mps;
        e.valid = aided || a.receiver.pvt.valid;
        if (aided && result.first_aided_s < 0.0) result.first_aided_s = e.t_s;
        switch (a.mode) {
          case aiding::NavMode::ultra: e.gnss_measurements = a.measuring_channels; break;
          case aiding::NavMode::tight: e.gnss_measurements = static_cast<int>(a.receiver.observations.size()); break;
          case aiding::NavMode::coast: e.gnss_measurements = 0; break;
          default: e.gnss_measurements = a.receiver.pvt.valid ? static_cast<int>(a.receiver.pvt.used_prns.size()) : 0;
        }
        const auto t = truth.at(e.t_s);
        e.valid = e.valid && t.has_value();  // an epoch past the truth's end cannot be scored
        if (e.valid) {
          e.error_ned_m = ned_offset_m(t->r_ecef_m, r);
          e.velocity_error_mps = (v - t->v_ecef_mps).norm();
        }
        result.epochs.push_back(e);
      },
      [&](const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
        if (ch.cn0_dbhz >= lost_dbhz) result.tracked_s[e.prn] += e.integration_s;
      });
  result.mode_changes = rx.mode_changes();
  result.satellite_exclusions = rx.satellite_exclusions();
  result.filter_restarts = rx.filter_restarts();
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace deepnav::cli
