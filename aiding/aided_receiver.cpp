#include "aiding/aided_receiver.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "aiding/galileo_clock_offset.hpp"
#include "aiding/gnss_coupling.hpp"
#include "aiding/imu_feed.hpp"
#include "aiding/innovation_monitor.hpp"
#include "aiding/ins_initializer.hpp"
#include "aiding/measurement_models.hpp"
#include "ins/frames.hpp"
#include "ins/rotations.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kRecentPvt_s = 3.0;

/// The ionosphere watch's fit with the troposphere's error fitted beside it. Each fix's
/// fit is the noisier for it (the two signatures differ mostly at low elevation), so the
/// window combines more fixes before the agreement test can pass.
DelayMismatchConfig beside_troposphere(DelayMismatchConfig c) {
  c.also_fitted = DelaySignature::troposphere_zenith;
  c.window_fixes *= 3;
  return c;
}

/// The coupling settings of an IF run: the receiver's atmosphere models with the filter's.
CouplingSettings coupling_settings(const AidedReceiverConfig& c) {
  CouplingSettings s;
  s.imu = c.imu;
  s.oscillator = c.oscillator;
  s.lever_arm_imu_to_antenna_b_m = c.lever_arm_imu_to_antenna_b_m;
  s.atmosphere = c.receiver.atmosphere;
  s.troposphere = c.troposphere;
  s.ionosphere = c.ionosphere;
  s.pvt_position_sigma_scale_m = c.pvt_position_sigma_scale_m;
  return s;
}

}  // namespace

struct AidedReceiver::Impl : ChannelAiding {
  AidedReceiverConfig cfg;
  CouplingSettings coupling;
  GnssReceiver rx;
  ImuLog imu;
  ImuFeed imu_feed;  ///< the log's samples, gaps and end (no INS where it has no data)
  InsInitializer init;
  std::optional<AidedNavigator> nav;
  UltraTightTracker ultra;
  ModeManager modes;
  InnovationMonitor innovations;
  SatelliteFaultMonitor faults;
  /// One atmosphere model watched for a mismatch with the signal, and what came of it.
  struct MismatchWatch {
    DelayMismatchDetector check;
    DelayMismatchReport report;
    /// The same fit with the other model's error fitted beside (DelayMismatchConfig::
    /// also_fitted), fed alongside from the start; its verdict counts once the other
    /// model's mismatch is found (the ionosphere's, beside the troposphere's).
    std::optional<DelayMismatchDetector> beside;
  };
  MismatchWatch troposphere_watch, ionosphere_watch;
  std::string start_method;
  int restarts = 0;
  int withheld = 0;  ///< solutions not published for their covariance
  bool withholding = false;
  double fs;
  double last_pvt_t_s = -1e9;
  int ranging = 0;
  int last_tight_satellites = 0;
  /// The Galileo ephemerides in use at the latest epoch (by SVID; empty without Galileo) and
  /// the offset of the Galileo clock the mixed fixes estimate.
  std::map<int, galileo::GalileoEphemeris> galileo_ephemerides;
  GalileoClockOffset galileo_offset;
  // The receiver's sum of clock steps the filter's clock has followed.
  double followed_clock_steps_s = 0.0;

  Impl(AidedReceiverConfig c, SampleSource& source, ImuLog log)
      : cfg(std::move(c)),
        coupling(coupling_settings(cfg)),
        rx(cfg.receiver, source),
        imu(std::move(log)),
        imu_feed(imu),
        init(cfg.imu, cfg.lever_arm_imu_to_antenna_b_m),
        ultra(cfg.ultra, source.sample_rate_hz(), cfg.receiver.pvt.range_errors,
              cfg.fault_exclusion ? &faults : nullptr, cfg.receiver.atmosphere),
        modes(cfg.mode, cfg.limits),
        faults(cfg.faults),
        troposphere_watch{DelayMismatchDetector(cfg.troposphere_mismatch), {}, {}},
        ionosphere_watch{DelayMismatchDetector(cfg.ionosphere_mismatch),
                         {},
                         DelayMismatchDetector(beside_troposphere(cfg.ionosphere_mismatch))},
        fs(source.sample_rate_hz()) {
    rx.set_channel_aiding(this);
  }

  ChannelController* controller_for(int prn) override { return ultra.controller_for(prn); }
  E1ChannelController* e1_controller_for(int svid) override { return ultra.e1_controller_for(svid); }

  void before_block() override {
    // Ultra-tight: the filter steers every channel it can. Loose/tight/coast: it steers only
    // channels whose signal has faded, so they are still aligned when it comes back.
    Engagement engage = Engagement::none;
    if (nav && modes.mode() == NavMode::ultra) engage = Engagement::all;
    else if (nav && modes.mode() != NavMode::scalar) engage = Engagement::faded_only;
    ultra.set_engagement(engage);
  }

  void after_block(const BlockSnapshot& block) override {
    const std::int64_t end = block.end_sample;
    const double t = static_cast<double>(end) / fs;
    propagate_to(t);
    follow_receiver_clock();
    if (nav && modes.mode() != NavMode::ultra && modes.mode() != NavMode::scalar)
      ultra.update_and_steer(*nav, block, false);
    if (nav && modes.mode() == NavMode::ultra) {
      std::vector<SatelliteInnovation> rows;
      const KalmanUpdate r = ultra.update_and_steer(*nav, block, true, cfg.fault_exclusion ? &rows : nullptr);
      innovations.add(t, r);
      if (cfg.fault_exclusion) report_exclusions(t, rows);
      if (end % static_cast<std::int64_t>(fs) < static_cast<std::int64_t>(fs / 100))
        spdlog::debug("t = {:.2f} s: ultra update {} measurements, {} rejected, max |nu|/sigma {:.2f}, {} steered", t,
                      ultra.measuring_channels(), r.rejected, r.max_normalized_innovation, ultra.steered_channels());
      check_health();
    }
    evaluate_modes(t, block);
  }

  std::vector<SignalPrediction> predict_untracked(const BlockSnapshot& block,
                                                  const std::vector<UntrackedSatellite>& satellites) override {
    // Only a filter that closes the loops itself predicts well enough, and only it can take
    // a weak channel over at once.
    std::vector<SignalPrediction> out;
    if (!nav || modes.mode() != NavMode::ultra || !nav->healthy()) return out;
    for (const UntrackedSatellite& s : satellites)
      if (const auto p = ultra.predict_signal(s.prn, s.ephemeris, *nav, block, cfg.receiver.pvt.elevation_mask_rad))
        out.push_back(*p);
    return out;
  }

  void propagate_to(double t) {
    // Where the IMU log has no data (a gap, its end) there is nothing to propagate the INS
    // with, so it stops (and restarts from the fixes after a gap) instead of driving
    // channels and publishing solutions from a state that no longer moves with the vehicle.
    imu_feed.advance(
        t,
        [&](const ImuSample& s) {
          if (!nav) init.add_imu(s);
          else if (s.t_s > nav->time_s()) nav->propagate(s);
        },
        [&](const ImuGap& g) {
          spdlog::warn("t = {:.2f} s: {}: INS stopped, scalar receiver until it restarts after the gap", t,
                       imu_feed.describe(g));
          stop_ins();  // an alignment under way starts over too: its samples end before the gap
        },
        [&] {
          spdlog::error("IMU data end at t = {:.2f} s but the IF data go on: INS stopped, scalar receiver from here",
                        imu_feed.last_sample_t_s());
          stop_ins();
        });
  }

  /// The scalar receiver re-sets its clock after fixes (steps of its bias); the filter's
  /// clock bias follows each step, taken from the receiver's own sum of steps.
  void follow_receiver_clock() {
    const double steps_s = rx.clock_steps_s();
    if (nav && steps_s != followed_clock_steps_s)
      nav->shift_clock_bias(gps::kSpeedOfLight_mps * (steps_s - followed_clock_steps_s));
    followed_clock_steps_s = steps_s;
  }

  void evaluate_modes(double t, const BlockSnapshot& block) {
    ModeInputs in;
    in.ins_ready = nav.has_value();
    in.filter_healthy = nav && nav->healthy();
    in.recent_pvt = t - last_pvt_t_s < kRecentPvt_s;
    in.ranging_satellites = modes.mode() == NavMode::ultra ? std::max(ranging, ultra.measuring_channels()) : ranging;
    in.steerable_channels = UltraTightTracker::count_steerable(block);
    if (nav) {
      const Eigen::Vector3d s = nav->position_sigma_ned_m();
      in.horizontal_sigma_m = std::hypot(s(0), s(1));
      in.velocity_sigma_mps = std::sqrt(nav->covariance().diagonal().segment<3>(kVel).maxCoeff());
    }
    const NavMode before = modes.mode();
    const NavMode now = modes.update(t, in);
    if (now != before) {
      spdlog::info("t = {:.2f} s: mode {} -> {} ({})", t, to_string(before), to_string(now),
                   modes.changes().back().reason);
      if (before == NavMode::ultra) ultra.release_all();
    }
  }

  void check_health() {
    if (!nav) return;
    if (!nav->healthy()) {
      spdlog::error("navigation filter failed ({}); INS restarted from the next fix", nav->health_reason());
    } else if (innovations.inconsistent()) {
      spdlog::error(
          "navigation filter rejects {} of its last {} measurement rows: it no longer agrees with the "
          "signals; INS restarted from the next fix",
          innovations.rejected(), innovations.rows());
    } else {
      return;
    }
    stop_ins();
    ++restarts;
  }

  /// Drops the INS and its filter; the initializer starts over from the next IMU samples
  /// and fixes.
  void stop_ins() {
    nav.reset();
    innovations.clear();
    faults.clear();
    ultra.release_all();
    init = InsInitializer(cfg.imu, cfg.lever_arm_imu_to_antenna_b_m);
  }

  /// A position or velocity no receiver can have (the vehicle's own limits aside): far
  /// from the Earth's surface, or faster than 12 km/s.
  static std::optional<std::string> implausible(const Eigen::Vector3d& r_ecef_m, const Eigen::Vector3d& v_ecef_mps) {
    const double r = r_ecef_m.norm(), v = v_ecef_mps.norm();
    if (!(r > 6.0e6 && r < 7.0e6)) return fmt::format("{:.0f} km from the Earth's centre", r / 1000.0);
    if (!(v < 1.2e4)) return fmt::format("moving at {:.3g} m/s", v);
    return std::nullopt;
  }

  /// Whether the filter's own horizontal uncertainty lets its solution be published; says
  /// so when that changes.
  bool supported_by_covariance(double t_s) {
    const Eigen::Vector3d sigma = nav->position_sigma_ned_m();
    const double horizontal = std::hypot(sigma(0), sigma(1));
    const bool supported = horizontal <= cfg.max_published_sigma_m;
    if (!supported && !withholding)
      spdlog::warn(
          "t = {:.2f} s: the aided solution's horizontal 1-sigma is {:.1f} m, over {:.1f} m: not published "
          "until measurements bring it back",
          t_s, horizontal, cfg.max_published_sigma_m);
    if (supported && withholding)
      spdlog::info("t = {:.2f} s: the aided solution's horizontal 1-sigma is {:.1f} m: published again", t_s,
                   horizontal);
    withholding = !supported;
    if (!supported) ++withheld;
    return supported;
  }

  void start_ins(const ReceiverEpoch& ep) {
    const GnssFix fix = alignment_fix(ep.pvt, ep.t_s, coupling.pvt_position_sigma_scale_m);
    const std::optional<InsStart> start = init.add_fix(fix);
    if (!start) return;
    const NavigatorConfig nc = navigator_config(coupling);
    // The fix's clock bias is against the receiver clock before this epoch's re-setting
    // (observe() steers it right after the fix, before the next block's follow): move it
    // onto the clock as it is now, and follow the steps from there.
    const double steps_s = rx.clock_steps_s();
    const double clock_step_m = gps::kSpeedOfLight_mps * (steps_s - followed_clock_steps_s);
    followed_clock_steps_s = steps_s;
    nav.emplace(start_navigator(*start, fix, nc, clock_step_m, ep.t_s));
    // A restart keeps what was found, started as when it was found.
    if (troposphere_watch.report.found_at_s) take_troposphere_state();
    if (ionosphere_watch.report.found_at_s && !nc.ionosphere.enabled) take_ionosphere_state();
    start_method = start->method;
  }

  void loose_update(const ReceiverEpoch& ep) {
    if (!ep.pvt.valid) return;
    // The PVT's velocity comes from Dopplers averaged over their last window (about 55 ms
    // before the fix): compared with the INS velocity at the mean of their times.
    double doppler_offset_s = 0.0;
    int dopplers = 0;
    for (const ChannelObservation& o : ep.observations) {
      const SatelliteId sat = o.satellite();
      if (std::find(ep.pvt.used_satellites.begin(), ep.pvt.used_satellites.end(), sat) == ep.pvt.used_satellites.end())
        continue;
      doppler_offset_s += o.doppler_offset_s;
      ++dopplers;
    }
    if (dopplers > 0) doppler_offset_s /= dopplers;
    // Not watched by the innovation monitor: the PVT's own errors come in runs under high
    // dynamics (its velocity model), and the gate turning them away is the right answer.
    aiding::loose_update(*nav,
                         {ep.t_s, ep.pvt, doppler_offset_s, Eigen::Vector3d::Constant(cfg.pvt_velocity_sigma_mps)},
                         coupling.pvt_position_sigma_scale_m);
  }

  /// The tight update: every satellite's pseudorange and Doppler rows, or (galileo_only, in
  /// ultra-tight mode) those of the Galileo satellites whose E1 channels the filter does not
  /// steer (before the system offset is known, or given back): their channels keep their
  /// own loops and reach the filter through their observables.
  void tight_update(const ReceiverEpoch& ep, bool galileo_only = false) {
    last_tight_satellites = 0;
    if (!ep.t_rx) return;
    RangeEpoch epoch{ep.t_s, *ep.t_rx, rx.iono(), {}};
    for (const ChannelObservation& o : ep.observations) {
      if (o.after_gap) continue;
      if (o.system == GnssSystem::gps && !galileo_only) {
        const Ephemeris* eph = rx.ephemeris(o.prn);
        if (eph == nullptr) continue;
        epoch.satellites.push_back({o.satellite(), *eph, o.pseudorange_m, o.cn0_dbhz, o.doppler_hz, o.doppler_offset_s,
                                    scalar_rate_sigma_mps(o.cn0_dbhz, cfg.receiver.tracking_loops.pll_hz,
                                                          1e-3 * cfg.receiver.tracking.coherent_ms_after_bit_sync)});
      } else if (const auto eph = galileo_ephemerides.find(o.prn); o.system == GnssSystem::galileo &&
                                                                   eph != galileo_ephemerides.end() &&
                                                                   !(galileo_only && ultra.e1_steered(o.prn))) {
        epoch.satellites.push_back(galileo_observation(o, eph->second));
      }
    }
    const PseudorangeWeighting weighting{cfg.receiver.pvt.range_errors, 1.0 / cfg.receiver.observation_rate_hz};
    std::vector<RangeMeasurement> ms, watched;
    for (const RangeMeasurement& m :
         tight_rows(*nav, epoch, coupling.atmosphere, cfg.receiver.pvt.elevation_mask_rad, weighting).used)
      (cfg.fault_exclusion && faults.excluded(m.satellite) ? watched : ms).push_back(m);
    last_tight_satellites = static_cast<int>(ms.size());
    if (ms.empty()) return;
    std::vector<SatelliteInnovation> rows;
    const KalmanUpdate r = nav->update_ranges(ms, cfg.fault_exclusion ? &rows : nullptr, watched);
    innovations.add(ep.t_s, r);
    if (cfg.fault_exclusion) report_exclusions(ep.t_s, rows);
  }

  /// A Galileo satellite's observables for the tight update: its pseudorange on the GPS clock
  /// (less the system offset the mixed fixes estimate, its sigma added) once that offset is
  /// known, and its Doppler (the E1 pilot PLL's noise at its tracking bandwidth).
  RangeObservation galileo_observation(const ChannelObservation& o, const galileo::GalileoEphemeris& eph) const {
    const GalileoReceiverSettings& g = cfg.receiver.galileo;
    RangeObservation r{
        o.satellite(),
        eph,
        std::nullopt,
        o.cn0_dbhz,
        o.doppler_hz,
        o.doppler_offset_s,
        scalar_rate_sigma_mps(o.cn0_dbhz, g.loops.tracking.pll_hz, 1e-3 * g.tracking.coherent_ms_after_sync)};
    if (const std::optional<double> offset_m = galileo_offset.offset_m()) {
      r.pseudorange_m = o.pseudorange_m - *offset_m;
      r.offset_sigma_m = galileo_offset.sigma_m();
    }
    return r;
  }

  /// How the logs name a satellite: "PRN  5" for GPS (as GPS-only runs always have), "E11".
  static std::string satellite_label(const SatelliteId& s) {
    return s.system == GnssSystem::gps ? fmt::format("PRN {:2d}", s.prn) : s.to_string();
  }

  /// Feeds the per-satellite fault monitor and logs each satellite it excludes or re-admits.
  void report_exclusions(double t_s, const std::vector<SatelliteInnovation>& rows) {
    const std::vector<SatelliteId> before = faults.excluded_satellites();
    faults.add(t_s, rows);
    const std::vector<SatelliteId> after = faults.excluded_satellites();
    for (const SatelliteId& s : after)
      if (std::find(before.begin(), before.end(), s) == before.end())
        spdlog::info("t = {:.2f} s: {} excluded: its pseudorange innovations disagree with the filter", t_s,
                     satellite_label(s));
    for (const SatelliteId& s : before)
      if (std::find(after.begin(), after.end(), s) == after.end())
        spdlog::info("t = {:.2f} s: {} agrees with the filter again: re-admitted", t_s, satellite_label(s));
  }

  /// Looks for atmosphere models the signal does not match, and once one is found has
  /// the filter estimate that model's residual whenever it takes pseudoranges (tight and
  /// ultra-tight; loose coupling has no rows that could see it).
  void watch_atmosphere(const ReceiverEpoch& ep) {
    if (!cfg.troposphere.enabled && cfg.troposphere.enable_on_mismatch) {
      find_mismatch(ep, troposphere_watch);
      if (troposphere_watch.report.found_at_s &&
          take_state(ep, troposphere_watch, nav && nav->troposphere_state_enabled())) {
        take_troposphere_state();
        spdlog::info("t = {:.2f} s: the aided filter estimates the zenith troposphere residual from now on", ep.t_s);
      }
    }
    // A missing troposphere reads as an ionosphere scale error too (-2.5 for the 2.3 m
    // zenith delay: both signatures grow towards the horizon, and one fit cannot tell them
    // apart); it is found first, by its wider margin. From then on the ionosphere watch
    // asks only what the troposphere's signature cannot explain (a signal lacking both).
    if (!cfg.ionosphere.enabled && cfg.ionosphere.enable_on_mismatch) {
      find_mismatch(ep, ionosphere_watch);
      if (ionosphere_watch.report.found_at_s &&
          take_state(ep, ionosphere_watch, nav && nav->ionosphere_state_enabled())) {
        take_ionosphere_state();
        // The troposphere state took the part of the missing ionosphere that looks like
        // troposphere: free it to give that part back.
        if (nav->troposphere_state_enabled()) nav->enable_troposphere_state(nav->troposphere_residual_m(), 1.0);
        spdlog::info("t = {:.2f} s: the aided filter estimates the ionosphere model's scale error from now on", ep.t_s);
      }
    }
  }

  /// The filter's troposphere state from the fixes' fit: the model's elevation pattern
  /// leaves the rows at once (from 0 the state took tens of seconds to separate from the
  /// height and clock, and the horizontal position kept the lean the error gave it).
  void take_troposphere_state() {
    troposphere_watch.report.height_room_m = nav->enable_troposphere_state(troposphere_watch.report.fitted_error, 0.5);
  }
  void take_ionosphere_state() {
    // Fitted beside the troposphere's error the scale is the less certain (measured: -1.24
    // to -1.34 where the signal lacks it all): room for the filter to settle it.
    const double sigma = troposphere_watch.report.found_at_s ? 0.5 : 0.2;
    ionosphere_watch.report.height_room_m = nav->enable_ionosphere_state(ionosphere_watch.report.fitted_error, sigma);
  }

  /// Whether the filter is to take a found mismatch's state now (a ranging mode, the
  /// state not yet on); notes when it first did.
  bool take_state(const ReceiverEpoch& ep, MismatchWatch& w, bool state_on) {
    const bool ranging_mode = modes.mode() == NavMode::tight || modes.mode() == NavMode::ultra;
    if (!nav || !ranging_mode || state_on) return false;
    if (!w.report.state_from_s) w.report.state_from_s = ep.t_s;
    return true;
  }

  void find_mismatch(const ReceiverEpoch& ep, MismatchWatch& w) {
    if (w.report.found_at_s) return;  // the detector takes no more epochs: its fit stays as found
    std::vector<RangeResidual> residuals;
    if (nav && modes.mode() == NavMode::ultra) {
      // Steered channels' pseudoranges echo the filter: the discriminators tell instead.
      residuals = ultra.mean_pseudorange_residuals();
    } else {
      if (!ep.pvt.valid) return;
      residuals = fix_residuals(ep.pvt, cn0_by_prn(ep));
    }
    w.check.add(residuals, cfg.receiver.pvt.range_errors);
    if (w.beside) w.beside->add(residuals, cfg.receiver.pvt.range_errors);
    // Only the ionosphere watch fits beside another model: the troposphere's, once found.
    const DelayMismatchDetector& verdict = w.beside && troposphere_watch.report.found_at_s ? *w.beside : w.check;
    w.report.fitted_error = verdict.fitted_error();
    const bool troposphere = &w == &troposphere_watch;
    spdlog::debug("t = {:.2f} s: {} model error fitted {:+.3f}", ep.t_s, troposphere ? "troposphere" : "ionosphere",
                  w.report.fitted_error);
    if (!verdict.mismatch()) return;
    w.report.found_at_s = ep.t_s;
    if (troposphere)
      spdlog::warn(
          "t = {:.2f} s: the fixes fit a troposphere model error of {:+.2f} m at the zenith: the signal does not "
          "match the receiver's troposphere model (IF without troposphere? then use --troposphere none)",
          ep.t_s, w.report.fitted_error);
    else
      spdlog::warn(
          "t = {:.2f} s: the fixes fit the ionosphere model's delay scaled by {:+.2f}: the signal does not match "
          "the receiver's ionosphere model (IF without ionosphere? then use --ionosphere none)",
          ep.t_s, 1.0 + w.report.fitted_error);
  }

  AidedEpoch on_observation(const ReceiverEpoch& ep) {
    if (ep.pvt.valid) last_pvt_t_s = ep.t_s;
    if (ep.t_rx) galileo_ephemerides = rx.galileo_ephemerides(*ep.t_rx);
    galileo_offset.add(ep.t_s, ep.pvt);
    ultra.set_galileo_offset(galileo_offset.offset_m(), galileo_offset.sigma_m());
    ranging = 0;
    for (const auto& o : ep.observations)
      if (o.system == GnssSystem::gps ? rx.ephemeris(o.prn) != nullptr : galileo_ephemerides.count(o.prn) > 0)
        ++ranging;
    // A hot start's coarse-time fix has no receiver clock behind it (its clock bias is
    // modulo 1 ms): the INS and its clock model start from the first fix with one.
    if (!nav && ep.pvt.valid && !ep.coarse_time && imu_feed.covers()) start_ins(ep);
    watch_atmosphere(ep);
    ultra.clear_pseudorange_residuals();
    last_tight_satellites = 0;
    if (nav) {
      if (modes.mode() == NavMode::loose) loose_update(ep);
      if (modes.mode() == NavMode::tight) tight_update(ep);
      if (modes.mode() == NavMode::ultra && !galileo_ephemerides.empty()) tight_update(ep, true);
      check_health();
    }
    AidedEpoch out;
    out.receiver = ep;
    out.coupling = out.mode = modes.mode();
    if (!nav || out.mode == NavMode::scalar) return out;
    out.r_ecef_m = nav->antenna_ecef_at(ep.t_s);
    out.v_ecef_mps = nav->antenna_velocity_ecef_mps();
    out.valid = out.r_ecef_m.allFinite() && out.v_ecef_mps.allFinite();
    if (!out.valid) return out;
    if (const auto why = implausible(out.r_ecef_m, out.v_ecef_mps)) {
      spdlog::error(
          "t = {:.2f} s: the aided solution left the physically possible ({}): not published; INS "
          "restarted from the next fix",
          ep.t_s, *why);
      stop_ins();
      ++restarts;
      out.valid = false;
      return out;
    }
    out.valid = supported_by_covariance(ep.t_s);
    if (!out.valid) return out;
    out.llh = wgs84::ecef_to_llh(out.r_ecef_m);
    out.v_ned_mps = ecef_to_ned_vector(out.llh, out.v_ecef_mps);
    const EulerAngles e = euler_from_quaternion(nav->ins().q_b_n);
    out.rpy_rad = Eigen::Vector3d(e.roll_rad, e.pitch_rad, e.yaw_rad);
    out.position_sigma_ned_m = nav->position_sigma_ned_m();
    out.clock_bias_m = nav->clock_bias_m();
    out.clock_drift_mps = nav->clock_drift_mps();
    out.steered_channels = ultra.steered_channels();
    out.measuring_channels = ultra.measuring_channels();
    switch (out.mode) {
      case NavMode::ultra:
        out.filter_satellites = ultra.measuring_channels() + last_tight_satellites;  // steered + unsteered Galileo rows
        break;
      case NavMode::tight:
        out.filter_satellites = last_tight_satellites;
        break;
      case NavMode::loose:
        out.filter_satellites = ep.pvt.valid ? static_cast<int>(ep.pvt.used_satellites.size()) : 0;
        break;
      default:
        out.filter_satellites = 0;
    }
    if (out.mode != NavMode::coast && out.filter_satellites < kMinSatellitesForAidedLabel) out.mode = NavMode::coast;
    return out;
  }
};

AidedReceiver::AidedReceiver(AidedReceiverConfig config, SampleSource& source, ImuLog imu,
                             std::optional<double> if_duration_s) {
  const std::string name = imu.source.empty() ? "the IMU log" : "IMU file " + imu.source;
  if (imu.samples.empty()) throw std::invalid_argument(name + " holds no samples");
  const double first = imu.samples.front().t_s, last = imu.samples.back().t_s;
  if (first > 1.0)
    throw std::invalid_argument(
        fmt::format("{} starts at t = {} s; it must cover the IF data from t = 0 (the first sample)", name, first));
  if (if_duration_s && last + 0.05 < *if_duration_s)
    throw std::invalid_argument(
        fmt::format("{}: the IMU log ends at t = {} s but the IF data last {} s", name, last, *if_duration_s));
  impl_ = std::make_unique<Impl>(std::move(config), source, std::move(imu));
}

AidedReceiver::~AidedReceiver() = default;

void AidedReceiver::run(const std::function<void(const AidedEpoch&)>& on_epoch,
                        const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation,
                        const std::function<void(double)>& progress) {
  impl_->rx.run([&](const ReceiverEpoch& ep) { on_epoch(impl_->on_observation(ep)); }, on_correlation, progress);
}

GnssReceiver& AidedReceiver::receiver() { return impl_->rx; }
const std::vector<ModeChange>& AidedReceiver::mode_changes() const { return impl_->modes.changes(); }
const std::string& AidedReceiver::ins_start_method() const { return impl_->start_method; }
int AidedReceiver::filter_restarts() const { return impl_->restarts; }
int AidedReceiver::satellite_exclusions() const { return impl_->faults.exclusions(); }
int AidedReceiver::withheld_solutions() const { return impl_->withheld; }
DelayMismatchReport AidedReceiver::troposphere_mismatch() const {
  DelayMismatchReport r = impl_->troposphere_watch.report;
  if (impl_->nav && impl_->nav->troposphere_state_enabled()) r.state_estimate = impl_->nav->troposphere_residual_m();
  return r;
}
DelayMismatchReport AidedReceiver::ionosphere_mismatch() const {
  DelayMismatchReport r = impl_->ionosphere_watch.report;
  if (impl_->nav && impl_->nav->ionosphere_state_enabled()) r.state_estimate = impl_->nav->ionosphere_scale_residual();
  return r;
}

}  // namespace deepnav::aiding
