#include "aiding/recorded_fusion.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <algorithm>
#include <deque>
#include <stdexcept>

#include "aiding/ins_initializer.hpp"
#include "aiding/measurement_models.hpp"
#include "ins/frames.hpp"
#include "ins/rotations.hpp"
#include "ins/wgs84.hpp"
#include "receiver/pvt/range_model.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kGpsToUnix_s = 315964800.0;  ///< 1980-01-06 minus 1970-01-01, in seconds

/// The stationarity detector: over the last window the specific force and the angular rate
/// each stay within a tolerance of their means (a bias does not matter), the mean specific
/// force is gravity's magnitude and the mean angular rate is no more than the tolerance plus
/// what the gyro's bias can be. The variation alone is not enough: a vehicle in a steady turn
/// or at constant speed with a quiet IMU passes it (the land circle with a tactical IMU did
/// at every epoch); the rate bound catches the turn, the GNSS speed (the caller's) the rest.
class StationarityDetector {
 public:
  StationarityDetector(const StationarityConfig& c, double gravity_mps2, double gyro_bias_radps)
      : cfg_(c), gravity_mps2_(gravity_mps2), gyro_bias_radps_(gyro_bias_radps) {}
  void add(const ImuSample& s, double dt) {
    if (dt <= 0.0) return;
    window_.push_back({s.t_s, s.dv_b_mps / dt, s.dtheta_b_rad / dt});
    while (!window_.empty() && s.t_s - window_.front().t > cfg_.window_s) window_.pop_front();
  }
  bool stationary() const {
    if (!cfg_.enabled || window_.size() < 5 || window_.back().t - window_.front().t < 0.8 * cfg_.window_s) return false;
    Eigen::Vector3d mf = Eigen::Vector3d::Zero(), mw = Eigen::Vector3d::Zero();
    for (const auto& e : window_) mf += e.f, mw += e.w;
    mf /= static_cast<double>(window_.size());
    mw /= static_cast<double>(window_.size());
    if (std::abs(mf.norm() - gravity_mps2_) > cfg_.accel_tolerance_mps2 ||
        mw.norm() > cfg_.gyro_tolerance_radps + gyro_bias_radps_)
      return false;
    for (const auto& e : window_)
      if ((e.f - mf).norm() > cfg_.accel_tolerance_mps2 || (e.w - mw).norm() > cfg_.gyro_tolerance_radps) return false;
    return true;
  }

 private:
  struct Entry {
    double t;
    Eigen::Vector3d f, w;
  };
  StationarityConfig cfg_;
  double gravity_mps2_, gyro_bias_radps_;
  std::deque<Entry> window_;
};

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
        if (st.prn == m.prn && st.code_residual_m) residuals.push_back(*st.code_residual_m);
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
          {"seconds_in_mode", seconds_in_mode}};
}

double fusion_time_s(const ObservationFile& obs, const GpsTime& t) {
  return t.seconds_since(GpsTime{obs.epochs.front().t.week, 0.0});
}

ImuTimeBase parse_imu_time_base(const std::string& name) {
  if (name == "week-seconds") return ImuTimeBase::week_seconds;
  if (name == "gps") return ImuTimeBase::gps_seconds;
  if (name == "unix-gps") return ImuTimeBase::unix_gps;
  throw std::invalid_argument("IMU time base '" + name + "' is not one of week-seconds, gps, unix-gps");
}

void to_fusion_axis(ImuLog& imu, ImuTimeBase base, const ObservationFile& obs) {
  const double week_start_gps_s = obs.epochs.front().t.week * kSecondsPerWeek;
  const double first_sow = obs.epochs.front().t.sow;
  const auto convert = [&](double t) {
    switch (base) {
      case ImuTimeBase::gps_seconds: return t - week_start_gps_s;
      case ImuTimeBase::unix_gps: return t - kGpsToUnix_s - week_start_gps_s;
      case ImuTimeBase::week_seconds:
        // Seconds of week: the week of the first epoch, or the next one across a rollover.
        return t < first_sow - kSecondsPerWeek / 2 ? t + kSecondsPerWeek : t;
    }
    return t;
  };
  for (ImuSample& s : imu.samples) s.t_s = convert(s.t_s);
  for (ImuGap& g : imu.gaps) g.t_before_s = convert(g.t_before_s), g.t_after_s = convert(g.t_after_s);
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
    throw std::invalid_argument(
        "the IMU log (" + std::to_string(imu_first) + " to " + std::to_string(imu_last) +
        " s of GPS week) does not overlap the observations (" + std::to_string(first) + " to " + std::to_string(last) +
        " s): check the IMU time base and offset");
}

void RecordedFusion::run(const std::vector<ProductSink*>& sinks) {
  const NavMode mode = cfg_.mode;
  const double t_first = fusion_time_s(obs_, obs_.epochs.front().t);
  PvtSolver solver(cfg_.pvt, cfg_.atmosphere);
  const IonoParameters iono = cfg_.iono ? *cfg_.iono : nav_.iono;
  InsInitializer init(cfg_.imu, cfg_.lever_arm_imu_to_antenna_b_m);
  std::optional<AidedNavigator> nav;
  const wgs84::Llh site = obs_.report.approx_position_ecef_m ? wgs84::ecef_to_llh(*obs_.report.approx_position_ecef_m)
                                                              : wgs84::Llh{0.7, 0.0, 0.0};
  StationarityDetector still(cfg_.stationarity, wgs84::normal_gravity_mps2(site.lat_rad, site.height_m),
                             3.0 * (cfg_.imu.gyro.bias_sigma + cfg_.imu.gyro.bias_instability_sigma));
  std::size_t next_imu = 0;
  double last_imu_t = -1e300;
  // A start at rest gyrocompasses: it needs a gyro whose bias is small against the Earth's
  // rate (the initializer's heading sigma reaches its 0.5 rad cap beyond this). A consumer
  // MEMS gyro (hundreds of deg/h) waits for the moving start (heading from the track).
  const double lat = obs_.report.approx_position_ecef_m ? wgs84::ecef_to_llh(*obs_.report.approx_position_ecef_m).lat_rad : 0.7;
  const bool rest_start =
      (cfg_.imu.gyro.bias_sigma + cfg_.imu.gyro.bias_instability_sigma) < 0.5 * wgs84::kEarthRate_radps * std::cos(lat);
  const int leap = nav_.leap_seconds_valid ? nav_.utc.delta_t_ls : 18;
  const double interval = obs_.report.nominal_interval_s > 0.0 ? obs_.report.nominal_interval_s : 1.0;
  std::optional<CarrierSmoother> smoother;
  if (cfg_.carrier_smoothing) smoother.emplace(cfg_.smoothing, interval, gps::kL1Wavelength_m);

  for (const ObservationEpoch& e : obs_.epochs) {
    const double t = fusion_time_s(obs_, e.t);
    while (next_imu < imu_.samples.size() && imu_.samples[next_imu].t_s <= t + 1e-9) {
      const ImuSample& s = imu_.samples[next_imu++];
      still.add(s, s.t_s - last_imu_t);
      last_imu_t = s.t_s;
      if (!nav) init.add_imu(s);
      else if (s.t_s > nav->time_s()) nav->propagate(s);
    }
    ++report_.epochs;
    ReceiverEpoch re;
    re.t_s = t - t_first;
    re.t_rx = e.t;
    FusionEpochTrace trace;
    trace.t_s = re.t_s;
    trace.clock_jump_m = e.clock_jump_m;
    std::map<int, Ephemeris> ephemerides;
    std::map<int, double> code;  // the pseudoranges the PVT and the filter take (smoothed or raw)
    std::vector<PseudorangeObservation> pvt_obs;
    bool dopplers = true;
    for (const GpsL1Observation& o : e.gps) {
      ChannelObservation c;
      c.prn = o.prn;
      c.pseudorange_m = o.pseudorange_m.value_or(0.0);
      c.doppler_hz = o.doppler_hz.value_or(0.0);
      c.carrier_phase_cycles = -o.carrier_phase_cycles.value_or(0.0);  // ours: accumulated Doppler
      c.cn0_dbhz = o.cn0_dbhz.value_or(0.0);
      c.after_gap = o.loss_of_lock;
      if (o.pseudorange_m) re.observations.push_back(c);
      FusionSatelliteTrace st;
      st.prn = o.prn;
      st.cn0_dbhz = o.cn0_dbhz.value_or(0.0);
      if (o.pseudorange_m) {
        code[o.prn] = *o.pseudorange_m;
        if (smoother) {
          const CarrierSmoother::Result r = smoother->add(o.prn, t, *o.pseudorange_m, o.carrier_phase_cycles,
                                                          o.doppler_hz, o.loss_of_lock, e.clock_jump_m);
          code[o.prn] = r.pseudorange_m;
          st.smoothing_epochs = r.epochs;
        }
      }
      trace.satellites.push_back(st);
      const Ephemeris* eph = nav_.select(o.prn, e.t);
      if (eph == nullptr || !o.pseudorange_m) continue;
      ephemerides[o.prn] = *eph;
      pvt_obs.push_back({o.prn, code[o.prn], o.doppler_hz.value_or(0.0), o.cn0_dbhz.value_or(40.0)});
      dopplers = dopplers && o.doppler_hz.has_value();
    }
    re.channels_tracking = static_cast<int>(e.gps.size());
    re.pvt = solver.solve(e.t, pvt_obs, ephemerides, iono);
    if (re.pvt.valid) ++report_.fixes;
    trace.pvt_valid = re.pvt.valid;
    trace.pvt_satellites = static_cast<int>(re.pvt.used_prns.size());
    const auto satellite_trace = [&](int prn) -> FusionSatelliteTrace& {
      for (FusionSatelliteTrace& st : trace.satellites)
        if (st.prn == prn) return st;
      throw std::logic_error("no trace of PRN " + std::to_string(prn));
    };
    for (const auto& [prn, el] : re.pvt.elevation_rad) satellite_trace(prn).elevation_deg = el * 180.0 / M_PI;

    if (nav && e.clock_jump_m != 0.0) {
      nav->shift_clock_bias(e.clock_jump_m);
      ++report_.clock_jumps_followed;
      spdlog::info("t = {:.2f} s: receiver clock re-set by {:.3f} us: filter clock follows", re.t_s,
                   e.clock_jump_m / gps::kSpeedOfLight_mps * 1e6);
    }
    int filter_satellites = 0;
    if (!nav && re.pvt.valid && dopplers && last_imu_t > t - 0.1) {
      GnssFix fix;
      fix.t_s = t;
      fix.r_antenna_ecef_m = re.pvt.r_ecef_m;
      fix.v_antenna_ecef_mps = re.pvt.v_ecef_mps;
      fix.clock_bias_m = re.pvt.clock_bias_m;
      fix.clock_drift_mps = re.pvt.clock_drift_mps;
      fix.horizontal_sigma_m = std::max(1.0, re.pvt.dops.hdop * cfg_.pvt_position_sigma_scale_m);
      fix.vertical_sigma_m = std::max(1.5, re.pvt.dops.vdop * cfg_.pvt_position_sigma_scale_m);
      const double speed = ecef_to_ned_vector(re.pvt.llh, re.pvt.v_ecef_mps).norm();
      std::optional<InsStart> start;
      if (rest_start || speed >= 0.2) start = init.add_fix(fix);
      if (start) {
        NavigatorConfig nc;
        nc.noise = process_noise_from(cfg_.imu, cfg_.oscillator);
        nc.lever_arm_imu_to_antenna_b_m = cfg_.lever_arm_imu_to_antenna_b_m;
        nc.gate_sigma = cfg_.gate_sigma;
        const double dt = start->state.t_s - t;
        nav.emplace(start->state, fix.clock_bias_m + fix.clock_drift_mps * dt, fix.clock_drift_mps, nc, start->uncertainty);
        report_.ins_start = start->method;
        report_.ins_start_t_s = re.t_s;
        const EulerAngles a = euler_from_quaternion(start->state.q_b_n);
        spdlog::info("t = {:.2f} s: INS started ({}): roll {:.1f} pitch {:.1f} yaw {:.1f} deg", re.t_s, start->method,
                     a.roll_rad * 180 / M_PI, a.pitch_rad * 180 / M_PI, a.yaw_rad * 180 / M_PI);
      }
    } else if (nav) {
      const double dt = t - nav->time_s();
      if (mode == NavMode::loose && re.pvt.valid) {
        const double vh = dopplers ? re.pvt.dops.hdop * cfg_.doppler_sigma_mps / std::sqrt(2.0) : 100.0;
        const double vv = dopplers ? re.pvt.dops.vdop * cfg_.doppler_sigma_mps : 100.0;
        const KalmanUpdate r = nav->update_position_velocity(
            re.pvt.r_ecef_m, re.pvt.v_ecef_mps,
            pvt_position_sigma_ned_m(re.pvt.dops.hdop, re.pvt.dops.vdop, cfg_.pvt_position_sigma_scale_m),
            Eigen::Vector3d(vh, vh, vv), dt, dt);
        report_.rows_rejected += r.rejected;
        trace.rows += r.rows;
        trace.rows_rejected += r.rejected;
        filter_satellites = static_cast<int>(re.pvt.used_prns.size());
      }
      if (mode == NavMode::tight) {
        const double bias = nav->clock_bias_m() + nav->clock_drift_mps() * dt;
        std::vector<RangeMeasurement> rows;
        for (const GpsL1Observation& o : e.gps) {
          const auto eph = ephemerides.find(o.prn);
          if (eph == ephemerides.end()) continue;
          RangeMeasurement m;
          m.prn = o.prn;
          m.time_offset_s = dt;
          m.geometry = predict_range(eph->second, e.t, bias, nav->antenna_ecef_at(t), nav->antenna_velocity_ecef_mps(), iono,
                                     cfg_.atmosphere);
          FusionSatelliteTrace& st = satellite_trace(o.prn);
          st.elevation_deg = m.geometry.elevation_rad * 180.0 / M_PI;
          if (m.geometry.elevation_rad < cfg_.pvt.elevation_mask_rad) continue;
          m.pseudorange_m = code.at(o.prn);
          m.pseudorange_sigma_m = cfg_.pseudorange_sigma_scale *
                                  std::sqrt(cfg_.pvt.range_errors.pseudorange_variance_m2(m.geometry.elevation_rad,
                                                                                          o.cn0_dbhz.value_or(40.0)));
          st.code_residual_m = *m.pseudorange_m - m.geometry.pseudorange_m(bias);
          if (o.doppler_hz) {
            m.rate_mps = -gps::kL1Wavelength_m * *o.doppler_hz;
            m.rate_sigma_mps = cfg_.doppler_sigma_mps;
            st.rate_residual_mps = *m.rate_mps - m.geometry.pseudorange_rate_mps(nav->antenna_velocity_ecef_mps(),
                                                                                  nav->clock_drift_mps());
          }
          rows.push_back(m);
        }
        if (!rows.empty()) {
          KalmanUpdate r = nav->update_ranges(rows);
          // Every pseudorange turned away, all by about the same amount: the receiver clock
          // stepped by less than the reader looks for (rinex_obs_reader.hpp), or the filter's
          // clock ran off. A common offset is a clock error, not four faulty satellites: the
          // clock takes it and the rows are offered again.
          if (const std::optional<double> step = common_code_offset(rows, r, trace); step) {
            nav->shift_clock_bias(*step);
            ++report_.clock_steps_absorbed;
            spdlog::info("t = {:.2f} s: every pseudorange {:.1f} m off the filter: its clock takes the step", re.t_s, *step);
            for (FusionSatelliteTrace& st : trace.satellites)
              if (st.code_residual_m) *st.code_residual_m -= *step;
            r = nav->update_ranges(rows);
          }
          report_.rows_rejected += r.rejected;
          trace.rows += r.rows;
          trace.rows_rejected += r.rejected;
          // The rows in order: each measurement's pseudorange row, then its rate row.
          std::size_t k = 0;
          for (const RangeMeasurement& m : rows) {
            FusionSatelliteTrace& st = satellite_trace(m.prn);
            if (m.pseudorange_m && k < r.normalized_innovations.size()) {
              st.code_normalized = -r.normalized_innovations[k];
              st.code_rejected = r.row_rejected[k];
              ++k;
            }
            if (m.rate_mps && k < r.row_rejected.size()) st.rate_rejected = r.row_rejected[k++];
          }
        }
        filter_satellites = static_cast<int>(rows.size());
      }
      // Not while the Dopplers say the antenna moves (a fix without Dopplers says nothing).
      const bool gnss_still = !re.pvt.valid || !dopplers ||
                              ecef_to_ned_vector(re.pvt.llh, re.pvt.v_ecef_mps).norm() <= cfg_.stationarity.max_gnss_speed_mps;
      if (gnss_still && still.stationary()) {
        const KalmanUpdate r = nav->update_zero_velocity(cfg_.stationarity.velocity_sigma_mps);
        if (r.applied) {
          ++report_.zero_velocity_updates;
          trace.zero_velocity = true;
        } else {
          ++report_.zero_velocity_rejected;
        }
      }
      if (!nav->healthy()) {
        spdlog::error("t = {:.2f} s: navigation filter failed ({}); INS restarted from the next fix", re.t_s,
                      nav->health_reason());
        nav.reset();
        init = InsInitializer(cfg_.imu, cfg_.lever_arm_imu_to_antenna_b_m);
        ++report_.filter_restarts;
      }
    }
    if (nav) trace.position_sigma_ned_m = nav->position_sigma_ned_m();
    trace.filter = nav.has_value();
    if (trace_) trace_(trace);

    PvtSolution solution = re.pvt;
    const bool from_filter = nav.has_value();
    if (from_filter) {
      solution.valid = true;
      solution.t = e.t;
      solution.r_ecef_m = nav->antenna_ecef_at(t);
      solution.v_ecef_mps = nav->antenna_velocity_ecef_mps();
      solution.llh = wgs84::ecef_to_llh(solution.r_ecef_m);
      solution.clock_bias_m = nav->clock_bias_m();
      solution.clock_drift_mps = nav->clock_drift_mps();
      ++report_.filter_epochs;
    }
    const std::string mode_name = from_filter ? to_string(mode) : "scalar";
    report_.seconds_in_mode[mode_name] += interval;
    const int measurements = from_filter ? (mode == NavMode::tight ? filter_satellites : static_cast<int>(re.pvt.used_prns.size()))
                                         : static_cast<int>(re.pvt.used_prns.size());
    const NavigationEpoch ne{re, solution, from_filter, mode_name,
                             from_filter ? filter_satellites : static_cast<int>(re.pvt.used_prns.size()), measurements, leap};
    for (ProductSink* s : sinks) s->on_epoch(ne);
  }
  if (smoother) {
    report_.smoothing_restarts = smoother->restarts();
    report_.smoothing_slips = smoother->slips();
    report_.smoothing_doppler_steps = smoother->doppler_steps();
  }
  for (ProductSink* s : sinks) s->finish(nav_);
}

}  // namespace deepnav::aiding
