#include "aiding/recorded_fusion.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "aiding/imu_feed.hpp"
#include "aiding/innovation_monitor.hpp"
#include "aiding/ins_initializer.hpp"
#include "ins/frames.hpp"
#include "ins/wgs84.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {
namespace {

/// Below this GNSS speed (m/s) a fix does not start an INS that cannot gyrocompass: the
/// moving start needs a direction of travel.
constexpr double kMovingStartSpeed_mps = 0.2;
/// The IMU must have reached this close to an epoch (s) for a fix there to start the INS.
constexpr double kStartImuLag_s = 0.1;
/// The C/N0 (dB-Hz) a pseudorange is weighed with when the recording has none.
constexpr double kMissingCn0_dbhz = 40.0;

/// The common offset of an epoch's pseudoranges from the filter when the gate turned every
/// one of them (four or more) away and they agree with each other: their median, when it
/// is over five times their spread about it (at least a metre).
std::optional<double> common_code_offset(const std::vector<RangeMeasurement>& rows, const KalmanUpdate& r,
                                         const FusionEpochTrace& trace) {
  std::vector<double> residuals;
  std::size_t k = 0;
  for (const RangeMeasurement& m : rows) {
    if (m.pseudorange_m) {
      if (k >= r.row_rejected.size() || !r.row_rejected[k]) return std::nullopt;
      for (const FusionSatelliteTrace& st : trace.satellites)
        if (st.prn == m.satellite.prn && st.code_residual_m) residuals.push_back(*st.code_residual_m);
      ++k;
    }
    if (m.rate_mps) ++k;
  }
  if (residuals.size() < 4) return std::nullopt;
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  const double mid = median(residuals);
  std::vector<double> spread;
  for (double x : residuals) spread.push_back(std::abs(x - mid));
  const double mad = median(spread);
  if (std::abs(mid) <= 5.0 * std::max(1.0, mad)) return std::nullopt;
  return mid;
}

FusionSatelliteTrace& satellite_trace(FusionEpochTrace& trace, int prn) {
  for (FusionSatelliteTrace& st : trace.satellites)
    if (st.prn == prn) return st;
  throw std::logic_error("no trace of PRN " + std::to_string(prn));
}

/// One epoch of the recording as the filter takes it.
struct FusionEpoch {
  const ObservationEpoch* recorded = nullptr;  ///< as read from the file
  double t = 0.0;                              ///< fusion axis
  ReceiverEpoch receiver;                      ///< t_s: since the first epoch; observables and PVT
  std::map<int, Ephemeris> ephemerides;        ///< of the satellites with a pseudorange
  std::map<int, double> code;                  ///< the pseudoranges the PVT and the filter take (smoothed or raw)
  bool dopplers = true;                        ///< every satellite offered to the PVT has a Doppler
  FusionEpochTrace trace;
};

/// One run over a recording: the IMU fed up to each epoch, the epoch's PVT, the INS start
/// or the filter's updates through the shared coupling steps, and the published solution.
class FusionRun {
 public:
  FusionRun(const RecordedFusionConfig& cfg, const ObservationFile& obs, const NavData& nav, const ImuLog& imu,
            RecordedFusionReport& report)
      : cfg_(cfg),
        obs_(obs),
        nav_(nav),
        imu_(imu),
        report_(report),
        imu_feed_(imu),
        t_first_(fusion_time_s(obs, obs.epochs.front().t)),
        solver_(cfg.pvt, cfg.coupling.atmosphere),
        iono_(cfg.iono ? *cfg.iono : nav.iono),
        site_(obs.report.approx_position_ecef_m ? wgs84::ecef_to_llh(*obs.report.approx_position_ecef_m)
                                                : wgs84::Llh{0.7, 0.0, 0.0}),
        init_(cfg.coupling.imu, cfg.coupling.lever_arm_imu_to_antenna_b_m),
        // At rest the mean rate is the gyro's bias: up to three of its sigmas.
        still_(cfg.stationarity, wgs84::normal_gravity_mps2(site_.lat_rad, site_.height_m),
               3.0 * gyro_bias_sigma_radps(cfg)),
        // A start at rest gyrocompasses: it needs a gyro whose bias is small against the
        // Earth's rate (the initializer's heading sigma reaches its 0.5 rad cap beyond
        // this). A consumer MEMS gyro (hundreds of deg/h) waits for the moving start
        // (heading from the track).
        rest_start_(gyro_bias_sigma_radps(cfg) < 0.5 * wgs84::kEarthRate_radps * std::cos(site_.lat_rad)),
        leap_(nav.leap_seconds_valid ? nav.utc.delta_t_ls : 18),
        interval_s_(obs.report.nominal_interval_s > 0.0 ? obs.report.nominal_interval_s : 1.0) {
    if (cfg.carrier_smoothing) smoother_.emplace(cfg.smoothing, interval_s_, gps::kL1Wavelength_m);
  }

  void epoch(const ObservationEpoch& e, const std::vector<ProductSink*>& sinks,
             const std::function<void(const FusionEpochTrace&)>& trace) {
    const double t = fusion_time_s(obs_, e.t);
    feed_imu_until(t);
    ++report_.epochs;
    FusionEpoch fe = read(e, t);
    if (nav_filter_ && e.clock_jump_m != 0.0) {
      nav_filter_->shift_clock_bias(e.clock_jump_m);
      ++report_.clock_jumps_followed;
      spdlog::info("t = {:.2f} s: receiver clock re-set by {:.3f} us: filter clock follows", fe.receiver.t_s,
                   e.clock_jump_m / gps::kSpeedOfLight_mps * 1e6);
    }
    int filter_satellites = 0;
    if (!nav_filter_ && fe.receiver.pvt.valid && fe.dopplers && imu_feed_.covers() &&
        imu_feed_.last_sample_t_s() > t - kStartImuLag_s) {
      try_start(fe);
    } else if (nav_filter_) {
      filter_satellites = update(fe);
    }
    if (nav_filter_) fe.trace.position_sigma_ned_m = nav_filter_->position_sigma_ned_m();
    fe.trace.filter = nav_filter_.has_value();
    if (trace) trace(fe.trace);
    publish(fe, filter_satellites, sinks);
  }

  void finish() {
    if (!smoother_) return;
    report_.smoothing_restarts = smoother_->restarts();
    report_.smoothing_slips = smoother_->slips();
    report_.smoothing_doppler_steps = smoother_->doppler_steps();
  }

 private:
  /// The gyro's bias (rad/s, 1 sigma): its turn-on bias and instability.
  static double gyro_bias_sigma_radps(const RecordedFusionConfig& c) {
    return c.coupling.imu.gyro.bias_sigma + c.coupling.imu.gyro.bias_instability_sigma;
  }

  /// The IMU up to the epoch at `t`. Where the log has no data (a gap, its end) the INS
  /// stops: the epochs there publish the single point, and after a gap the INS starts
  /// again from the fixes.
  void feed_imu_until(double t) {
    imu_feed_.advance(
        t,
        [&](const ImuSample& s) {
          still_.add(s, s.t_s - imu_feed_.last_sample_t_s());
          if (!nav_filter_) init_.add_imu(s);
          else if (s.t_s > nav_filter_->time_s()) nav_filter_->propagate(s);
        },
        [&](const ImuGap& g) {
          ++report_.imu_gap_stops;
          spdlog::warn("t = {:.2f} s: {}: INS stopped, single-point solutions until it restarts after the gap",
                       t - t_first_, imu_feed_.describe(g, t_first_));
          stop_ins();
        },
        [&] {
          report_.imu_end_t_s = imu_feed_.last_sample_t_s() - t_first_;
          spdlog::warn(
              "t = {:.2f} s: the IMU log ends at t = {:.2f} s but the observations go on to t = {:.2f} s: INS "
              "stopped, single-point solutions from here",
              t - t_first_, *report_.imu_end_t_s, fusion_time_s(obs_, obs_.epochs.back().t) - t_first_);
          stop_ins();
        });
  }

  /// Drops the INS and its filter; the initializer starts over from the next IMU samples.
  void stop_ins() {
    nav_filter_.reset();
    innovations_.clear();
    init_ = InsInitializer(cfg_.coupling.imu, cfg_.coupling.lever_arm_imu_to_antenna_b_m);
  }

  /// The epoch's observables (carrier-smoothed code), ephemerides and PVT, and its trace.
  FusionEpoch read(const ObservationEpoch& e, double t) {
    FusionEpoch fe;
    fe.recorded = &e;
    fe.t = t;
    ReceiverEpoch& re = fe.receiver;
    re.t_s = t - t_first_;
    re.t_rx = e.t;
    fe.trace.t_s = re.t_s;
    fe.trace.clock_jump_m = e.clock_jump_m;
    std::vector<PseudorangeObservation> pvt_obs;
    for (const GpsL1Observation& o : e.gps) {
      ChannelObservation c;
      c.prn = o.prn;
      c.pseudorange_m = o.pseudorange_m.value_or(0.0);
      c.doppler_hz = o.doppler_hz.value_or(0.0);
      c.doppler_offset_s = cfg_.doppler_time_offset_s;
      c.carrier_phase_cycles = -o.carrier_phase_cycles.value_or(0.0);  // ours: accumulated Doppler
      c.cn0_dbhz = o.cn0_dbhz.value_or(0.0);
      c.after_gap = o.loss_of_lock;
      if (o.pseudorange_m) re.observations.push_back(c);
      FusionSatelliteTrace st;
      st.prn = o.prn;
      st.cn0_dbhz = o.cn0_dbhz.value_or(0.0);
      if (o.pseudorange_m) {
        fe.code[o.prn] = *o.pseudorange_m;
        if (smoother_) {
          const CarrierSmoother::Result r = smoother_->add(o.prn, t, *o.pseudorange_m, o.carrier_phase_cycles,
                                                           o.doppler_hz, o.loss_of_lock, e.clock_jump_m);
          fe.code[o.prn] = r.pseudorange_m;
          st.smoothing_epochs = r.epochs;
        }
      }
      fe.trace.satellites.push_back(st);
      const Ephemeris* eph = nav_.select(o.prn, e.t);
      if (eph == nullptr || !o.pseudorange_m) continue;
      fe.ephemerides[o.prn] = *eph;
      pvt_obs.push_back({o.prn, fe.code[o.prn], o.doppler_hz.value_or(0.0), o.cn0_dbhz.value_or(kMissingCn0_dbhz)});
      fe.dopplers = fe.dopplers && o.doppler_hz.has_value();
    }
    re.channels_tracking = static_cast<int>(e.gps.size());
    re.pvt = solver_.solve(e.t, pvt_obs, fe.ephemerides, iono_);
    if (re.pvt.valid) ++report_.fixes;
    fe.trace.pvt_valid = re.pvt.valid;
    fe.trace.pvt_satellites = static_cast<int>(re.pvt.used_satellites.size());
    for (const auto& [sat, el] : re.pvt.elevation_rad)
      if (sat.system == GnssSystem::gps) satellite_trace(fe.trace, sat.prn).elevation_deg = el * 180.0 / M_PI;
    return fe;
  }

  /// The GNSS speed (m/s) of the epoch's PVT.
  static double pvt_speed_mps(const PvtSolution& pvt) { return ecef_to_ned_vector(pvt.llh, pvt.v_ecef_mps).norm(); }

  void try_start(const FusionEpoch& fe) {
    const GnssFix fix = alignment_fix(fe.receiver.pvt, fe.t, cfg_.coupling.pvt_position_sigma_scale_m);
    if (!rest_start_ && pvt_speed_mps(fe.receiver.pvt) < kMovingStartSpeed_mps) return;
    const std::optional<InsStart> start = init_.add_fix(fix);
    if (!start) return;
    nav_filter_.emplace(start_navigator(*start, fix, navigator_config(cfg_.coupling), 0.0, fe.receiver.t_s));
    report_.ins_start = start->method;
    report_.ins_start_t_s = fe.receiver.t_s;
  }

  /// The epoch's updates in the run's mode, a zero-velocity update when at rest, and a
  /// restart of a failed filter. Returns the satellites the coupling took.
  int update(FusionEpoch& fe) {
    int filter_satellites = 0;
    if (cfg_.mode == NavMode::loose && fe.receiver.pvt.valid) filter_satellites = loose(fe);
    if (cfg_.mode == NavMode::tight) filter_satellites = tight(fe);
    zero_velocity(fe);
    if (!nav_filter_->healthy()) {
      spdlog::error("t = {:.2f} s: navigation filter failed ({}); INS restarted from the next fix", fe.receiver.t_s,
                    nav_filter_->health_reason());
    } else if (innovations_.inconsistent()) {
      spdlog::error(
          "t = {:.2f} s: navigation filter rejects {} of its last {} measurement rows: it no longer agrees with the "
          "observations; INS restarted from the next fix",
          fe.receiver.t_s, innovations_.rejected(), innovations_.rows());
    } else {
      return filter_satellites;
    }
    stop_ins();
    ++report_.filter_restarts;
    return filter_satellites;
  }

  void count_rows(FusionEpoch& fe, const KalmanUpdate& r) {
    report_.rows_rejected += r.rejected;
    fe.trace.rows += r.rows;
    fe.trace.rows_rejected += r.rejected;
  }

  int loose(FusionEpoch& fe) {
    const PvtSolution& pvt = fe.receiver.pvt;
    // The velocity from the Dopplers weighs as their sigma through the fix's geometry; a
    // fix without them has a velocity that says nothing.
    const double vh = fe.dopplers ? pvt.dops.hdop * cfg_.doppler_sigma_mps / std::sqrt(2.0) : 100.0;
    const double vv = fe.dopplers ? pvt.dops.vdop * cfg_.doppler_sigma_mps : 100.0;
    const LooseFix fix{fe.t, pvt, cfg_.doppler_time_offset_s, Eigen::Vector3d(vh, vh, vv)};
    count_rows(fe, loose_update(*nav_filter_, fix, cfg_.coupling.pvt_position_sigma_scale_m));
    return static_cast<int>(pvt.used_satellites.size());
  }

  int tight(FusionEpoch& fe) {
    RangeEpoch epoch{fe.t, *fe.receiver.t_rx, iono_, {}};
    for (const GpsL1Observation& o : fe.recorded->gps) {
      const auto eph = fe.ephemerides.find(o.prn);
      if (eph == fe.ephemerides.end()) continue;
      epoch.satellites.push_back({SatelliteId{GnssSystem::gps, o.prn}, eph->second, fe.code.at(o.prn),
                                  o.cn0_dbhz.value_or(kMissingCn0_dbhz), o.doppler_hz, cfg_.doppler_time_offset_s,
                                  cfg_.doppler_sigma_mps});
    }
    // Each epoch's row carries the range model's terms whole, whatever the epoch rate (the
    // IF path shares them among the rows of a second); pseudorange_sigma_scale tunes it.
    const PseudorangeWeighting weighting{cfg_.pvt.range_errors, 1.0, cfg_.pseudorange_sigma_scale};
    const TightRows rows =
        tight_rows(*nav_filter_, epoch, cfg_.coupling.atmosphere, cfg_.pvt.elevation_mask_rad, weighting);
    for (const RangeMeasurement& m : rows.below_mask)
      satellite_trace(fe.trace, m.satellite.prn).elevation_deg = m.geometry.elevation_rad * 180.0 / M_PI;
    for (const RangeMeasurement& m : rows.used) {
      FusionSatelliteTrace& st = satellite_trace(fe.trace, m.satellite.prn);
      st.elevation_deg = m.geometry.elevation_rad * 180.0 / M_PI;
      st.code_residual_m = *m.pseudorange_m - nav_filter_->predicted_pseudorange_m(m);
      if (m.rate_mps) st.rate_residual_mps = *m.rate_mps - nav_filter_->predicted_rate_mps(m);
    }
    if (!rows.used.empty()) apply_ranges(fe, rows.used);
    return static_cast<int>(rows.used.size());
  }

  void apply_ranges(FusionEpoch& fe, const std::vector<RangeMeasurement>& rows) {
    KalmanUpdate r = nav_filter_->update_ranges(rows);
    // Every pseudorange turned away, all by about the same amount: the receiver clock
    // stepped by less than the reader looks for (rinex_obs_reader.hpp), or the filter's
    // clock ran off. A common offset is a clock error, not four faulty satellites: the
    // clock takes it and the rows are offered again.
    if (const std::optional<double> step = common_code_offset(rows, r, fe.trace); step) {
      nav_filter_->shift_clock_bias(*step);
      ++report_.clock_steps_absorbed;
      spdlog::info("t = {:.2f} s: every pseudorange {:.1f} m off the filter: its clock takes the step", fe.receiver.t_s,
                   *step);
      for (FusionSatelliteTrace& st : fe.trace.satellites)
        if (st.code_residual_m) *st.code_residual_m -= *step;
      r = nav_filter_->update_ranges(rows);
    }
    count_rows(fe, r);
    innovations_.add(fe.t, r);
    // The rows in order: each measurement's pseudorange row, then its rate row.
    std::size_t k = 0;
    for (const RangeMeasurement& m : rows) {
      FusionSatelliteTrace& st = satellite_trace(fe.trace, m.satellite.prn);
      if (m.pseudorange_m && k < r.normalized_innovations.size()) {
        st.code_normalized = -r.normalized_innovations[k];
        st.code_rejected = r.row_rejected[k];
        ++k;
      }
      if (m.rate_mps && k < r.row_rejected.size()) st.rate_rejected = r.row_rejected[k++];
    }
  }

  void zero_velocity(FusionEpoch& fe) {
    // Not while the Dopplers say the antenna moves (a fix without Dopplers says nothing).
    const PvtSolution& pvt = fe.receiver.pvt;
    const bool gnss_still = !pvt.valid || !fe.dopplers || pvt_speed_mps(pvt) <= cfg_.stationarity.max_gnss_speed_mps;
    if (!gnss_still || !still_.stationary()) return;
    const KalmanUpdate r = nav_filter_->update_zero_velocity(cfg_.stationarity.velocity_sigma_mps);
    if (r.applied) {
      ++report_.zero_velocity_updates;
      fe.trace.zero_velocity = true;
    } else {
      ++report_.zero_velocity_rejected;
    }
  }

  /// The filter's solution where it runs, else the PVT's, to every sink.
  void publish(const FusionEpoch& fe, int filter_satellites, const std::vector<ProductSink*>& sinks) {
    const ReceiverEpoch& re = fe.receiver;
    PvtSolution solution = re.pvt;
    const bool from_filter = nav_filter_.has_value();
    if (from_filter) {
      solution.valid = true;
      solution.t = fe.recorded->t;
      solution.r_ecef_m = nav_filter_->antenna_ecef_at(fe.t);
      solution.v_ecef_mps = nav_filter_->antenna_velocity_ecef_mps();
      solution.llh = wgs84::ecef_to_llh(solution.r_ecef_m);
      solution.clock_bias_m = nav_filter_->clock_bias_m();
      solution.clock_drift_mps = nav_filter_->clock_drift_mps();
      ++report_.filter_epochs;
    }
    const std::string mode_name = from_filter ? to_string(cfg_.mode) : "scalar";
    report_.seconds_in_mode[mode_name] += interval_s_;
    const int pvt_satellites = static_cast<int>(re.pvt.used_satellites.size());
    const int measurements = from_filter && cfg_.mode == NavMode::tight ? filter_satellites : pvt_satellites;
    const NavigationEpoch ne{
        re, solution, from_filter, mode_name, from_filter ? filter_satellites : pvt_satellites, measurements, leap_};
    for (ProductSink* s : sinks) s->on_epoch(ne);
  }

  const RecordedFusionConfig& cfg_;
  const ObservationFile& obs_;
  const NavData& nav_;
  const ImuLog& imu_;
  RecordedFusionReport& report_;
  ImuFeed imu_feed_;
  double t_first_;
  PvtSolver solver_;
  IonoParameters iono_;
  wgs84::Llh site_;
  InsInitializer init_;
  std::optional<AidedNavigator> nav_filter_;
  /// Tight: how many range rows the gate turns away (a filter that no longer agrees with
  /// the observations restarts, as in `deepnav run`).
  InnovationMonitor innovations_;
  StationarityDetector still_;
  bool rest_start_;
  int leap_;
  double interval_s_;
  std::optional<CarrierSmoother> smoother_;
};

}  // namespace

nlohmann::json RecordedFusionReport::json() const {
  return {{"epochs", epochs},
          {"fixes", fixes},
          {"filter_epochs", filter_epochs},
          {"zero_velocity_updates", zero_velocity_updates},
          {"zero_velocity_rejected", zero_velocity_rejected},
          {"clock_jumps_followed", clock_jumps_followed},
          {"clock_steps_absorbed", clock_steps_absorbed},
          {"filter_restarts", filter_restarts},
          {"rows_rejected", rows_rejected},
          {"smoothing_restarts", smoothing_restarts},
          {"smoothing_slips", smoothing_slips},
          {"smoothing_doppler_steps", smoothing_doppler_steps},
          {"ins_start", ins_start},
          {"ins_start_s", ins_start_t_s ? nlohmann::json(*ins_start_t_s) : nlohmann::json(nullptr)},
          {"imu_gap_stops", imu_gap_stops},
          {"imu_end_s", imu_end_t_s ? nlohmann::json(*imu_end_t_s) : nlohmann::json(nullptr)},
          {"seconds_in_mode", seconds_in_mode}};
}

RecordedFusion::RecordedFusion(RecordedFusionConfig config, const ObservationFile& obs, const NavData& nav, ImuLog imu)
    : cfg_(std::move(config)), obs_(obs), nav_(nav), imu_(std::move(imu)) {
  if (cfg_.mode != NavMode::loose && cfg_.mode != NavMode::tight)
    throw std::invalid_argument(std::string("fuse couples loose or tight, not ") + to_string(cfg_.mode));
  if (obs_.epochs.empty()) throw std::invalid_argument("no observation epochs");
  if (imu_.samples.empty()) throw std::invalid_argument("the IMU log holds no samples");
  const double first = fusion_time_s(obs_, obs_.epochs.front().t), last = fusion_time_s(obs_, obs_.epochs.back().t);
  const double imu_first = imu_.samples.front().t_s, imu_last = imu_.samples.back().t_s;
  if (imu_last < first || imu_first > last)
    throw std::invalid_argument("the IMU log (" + std::to_string(imu_first) + " to " + std::to_string(imu_last) +
                                " s of GPS week) does not overlap the observations (" + std::to_string(first) + " to " +
                                std::to_string(last) + " s): check the IMU time base and offset");
}

void RecordedFusion::run(const std::vector<ProductSink*>& sinks) {
  FusionRun fusion(cfg_, obs_, nav_, imu_, report_);
  for (const ObservationEpoch& e : obs_.epochs) fusion.epoch(e, sinks, trace_);
  fusion.finish();
  for (ProductSink* s : sinks) s->finish(nav_);
}

}  // namespace deepnav::aiding
