#include "receiver/pvt/coarse_time_solver.hpp"

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "ins/frames.hpp"
#include "receiver/pvt/coarse_time_checks.hpp"
#include "receiver/pvt/coarse_time_diagnosis.hpp"
#include "receiver/pvt/coarse_time_search.hpp"
#include "receiver/pvt/range_model.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr std::size_t kMinSatellites = 6;  // five unknowns and one to test the whole milliseconds

/// The measurements as the fits take them.
struct Snapshot {
  std::vector<CoarseTimeSatellite> satellites;
  std::vector<DopplerSatellite> dopplers;
  std::vector<int> without_ephemeris;
};

Snapshot prepare(const std::vector<SnapshotMeasurement>& measurements, const std::map<int, Ephemeris>& ephemerides,
                 const GpsTime& t_hint, const CoarseTimeConfig& config) {
  Snapshot s;
  for (const SnapshotMeasurement& m : measurements) {
    const auto it = ephemerides.find(m.prn);
    if (it == ephemerides.end()) {
      s.without_ephemeris.push_back(m.prn);
      continue;
    }
    // Code tracking noise goes as 1 / sqrt(C/N0).
    const double sigma_m = config.code_sigma_m * std::pow(10.0, (config.reference_cn0_dbhz - m.cn0_dbhz) / 20.0);
    s.satellites.push_back({m.prn, &it->second, submillisecond_pseudorange_m(m.code_phase_chips, t_hint), sigma_m});
    if (m.doppler_hz) s.dopplers.push_back({m.prn, &it->second, *m.doppler_hz});
  }
  return s;
}

void check_position_hint(const Eigen::Vector3d& r_ecef_m) {
  constexpr double kMaxAbsHeight_m = 100e3;
  const bool finite = r_ecef_m.allFinite() && r_ecef_m.norm() > 1e6;  // ecef_to_llh needs to be off the centre
  if (!finite || !(std::abs(wgs84::ecef_to_llh(r_ecef_m).height_m) <= kMaxAbsHeight_m))
    throw std::invalid_argument(fmt::format(
        "coarse-time hints: position_ecef_m ({}, {}, {}) m is not a place within {:.0f} km of the Earth's surface",
        r_ecef_m.x(), r_ecef_m.y(), r_ecef_m.z(), kMaxAbsHeight_m / 1e3));
}

std::string km(double metres) { return fmt::format("{:.0f} km", metres / 1e3); }

std::string place(const Eigen::Vector3d& r_ecef_m) {
  const wgs84::Llh llh = wgs84::ecef_to_llh(r_ecef_m);
  return fmt::format("{:.4f} deg, {:.4f} deg", llh.lat_rad * 180.0 / std::numbers::pi,
                     llh.lon_rad * 180.0 / std::numbers::pi);
}

/// A value modulo c * 1 ms, in [-c * 0.5 ms, c * 0.5 ms).
double wrapped_to_half_period(double range_m) {
  return range_m - kCodePeriodRange_m * std::floor(range_m / kCodePeriodRange_m + 0.5);
}

void fill_dops(CoarseTimeFix& fix, const Eigen::MatrixXd& H) {
  const Eigen::MatrixXd Q = (H.transpose() * H).inverse();
  const Eigen::Matrix3d C = C_e_n(fix.llh.lat_rad, fix.llh.lon_rad);
  const Eigen::Matrix3d Qn = C * Q.topLeftCorner<3, 3>() * C.transpose();
  fix.dops.gdop = std::sqrt(Q.topLeftCorner<4, 4>().trace());
  fix.dops.pdop = std::sqrt(Q.topLeftCorner<3, 3>().trace());
  fix.dops.hdop = std::sqrt(Qn(0, 0) + Qn(1, 1));
  fix.dops.vdop = std::sqrt(Qn(2, 2));
  fix.dops.tdop = std::sqrt(Q(3, 3));
  fix.coarse_time_dop_s_per_m = std::sqrt(Q(4, 4));
}

/// The receiver clock drift at a fix: what the Dopplers leave once the satellites' own
/// range rates to the fix are taken out (their mean; equal weights).
std::optional<double> clock_drift_at(const CoarseTimeFix& fix, const std::vector<DopplerSatellite>& dopplers,
                                     const CoarseTimeContext& context) {
  if (dopplers.empty()) return std::nullopt;
  double sum = 0.0;
  for (const DopplerSatellite& d : dopplers) {
    const RangePrediction p = predict_range(*d.ephemeris, fix.receive_time, 0.0, fix.r_ecef_m, Eigen::Vector3d::Zero(),
                                            context.iono, context.atmosphere);
    sum += -gps::kL1Wavelength_m * d.doppler_hz - p.pseudorange_rate_mps(Eigen::Vector3d::Zero(), 0.0);
  }
  return sum / static_cast<double>(dopplers.size());
}

CoarseTimeFix fix_from(const CheckedCoarseTimeFit& checked, CoarseTimeStart start, int candidates,
                       const Snapshot& snapshot, const CoarseTimeContext& context) {
  CoarseTimeFix fix;
  const CoarseTimeFit& fit = checked.fit;
  fix.valid = true;
  fix.start = start;
  fix.r_ecef_m = fit.state.r_ecef_m;
  fix.llh = wgs84::ecef_to_llh(fix.r_ecef_m);
  fix.clock_bias_m = wrapped_to_half_period(fit.state.clock_bias_m);
  fix.coarse_time_correction_s = fit.state.time_correction_s;
  fix.receive_time = context.t_hint.plus_seconds(fit.state.time_correction_s);
  fill_dops(fix, fit.H);
  for (std::size_t k = 0; k < checked.used.size(); ++k) {
    const int prn = checked.used[k].prn;
    fix.used_prns.push_back(prn);
    fix.pseudorange_m[prn] = fit.pseudorange_m[k];
    fix.residuals_m[prn] = fit.residuals_m(static_cast<Eigen::Index>(k));
    fix.elevation_rad[prn] = fit.elevation_rad[k];
  }
  fix.excluded_prns = checked.excluded_prns;
  fix.repaired_ms = checked.repaired_ms;
  fix.without_ephemeris = snapshot.without_ephemeris;
  fix.clock_drift_mps = clock_drift_at(fix, snapshot.dopplers, context);
  const auto n = static_cast<double>(checked.used.size());
  fix.quality = {std::sqrt(fit.residuals_m.squaredNorm() / n),
                 checked.test.statistic,
                 checked.test.threshold,
                 checked.test.dof,
                 checked.passed,
                 fit.iterations,
                 candidates};
  return fix;
}

CoarseTimeFix refusal(std::string reason, SuspectHint suspect, const Snapshot& snapshot) {
  CoarseTimeFix fix;
  fix.reason = std::move(reason);
  fix.suspect = suspect;
  fix.without_ephemeris = snapshot.without_ephemeris;
  return fix;
}

std::string candidate_note(const CoarseTimeSearch& search) {
  const bool around_doppler = search.doppler && search.doppler->valid;
  std::string note = fmt::format("{} sets of whole milliseconds tried{}{}{}", search.candidates,
                                 around_doppler ? " around the Doppler position" : "",
                                 around_doppler && search.searched_visible_region ? " and" : "",
                                 search.searched_visible_region ? " over the region that sees every satellite" : "");
  if (!search.reason.empty()) note += "; " + search.reason;
  return note;
}

/// The refusal when several places fit, naming the first two.
CoarseTimeFix ambiguity(const CoarseTimeSearch& search, const Snapshot& snapshot) {
  const Eigen::Vector3d& a = search.fixes[0].fit.state.r_ecef_m;
  const Eigen::Vector3d& b = search.fixes[1].fit.state.r_ecef_m;
  return refusal(fmt::format("the code phases fit {} places at the hinted time, e.g. ({}) and ({}), {} apart: "
                             "give a position hint or Dopplers to choose",
                             search.fixes.size(), place(a), place(b), km((a - b).norm())),
                 SuspectHint::ambiguous, snapshot);
}

}  // namespace

std::string to_string(CoarseTimeStart start) {
  switch (start) {
    case CoarseTimeStart::position_hint:
      return "position hint";
    case CoarseTimeStart::doppler:
      return "Doppler position";
    case CoarseTimeStart::grid:
      return "grid";
  }
  return "?";
}

std::string to_string(SuspectHint suspect) {
  switch (suspect) {
    case SuspectHint::none:
      return "none";
    case SuspectHint::position:
      return "position";
    case SuspectHint::time:
      return "time";
    case SuspectHint::unknown:
      return "unknown";
    case SuspectHint::ambiguous:
      return "ambiguous";
  }
  return "?";
}

namespace {

class CoarseTimeRun {
 public:
  CoarseTimeRun(const CoarseTimeConfig& config, Snapshot snapshot, CoarseTimeContext context)
      : cfg_(config), snap_(std::move(snapshot)), ctx_(context) {}

  CoarseTimeFix with_position_hint(const Eigen::Vector3d& hint) const {
    CoarseTimeState start;
    start.r_ecef_m = hint;
    const WholeMilliseconds ms = resolve_whole_milliseconds(snap_.satellites, ctx_, start);
    const CheckedCoarseTimeFit checked = checked_coarse_time_fit(snap_.satellites, ms, ctx_, start, cfg_.integrity);
    const std::string why = checked.passed ? hint_violation(checked, hint) : checked.reason;
    if (why.empty()) return fix_from(checked, CoarseTimeStart::position_hint, 1, snap_, ctx_);
    return diagnose(hint, why);
  }

  CoarseTimeFix without_position_hint() const {
    const CoarseTimeSearch search = search_without_position(snap_.satellites, snap_.dopplers, ctx_, cfg_);
    if (search.fixes.size() == 1) return searched_fix(search);
    if (search.fixes.size() > 1) return ambiguity(search, snap_);
    if (search.too_few_satellites) return refusal(search.reason, SuspectHint::none, snap_);
    if (search.beyond_time_tolerance.size() == 1) return time_refusal(search.beyond_time_tolerance.front(), "there");
    return refusal(fmt::format("no place fits the code phases at the hinted time ({}): the time hint is off by more "
                               "than the +-{:.0f} s the method tolerates, or the measurements are wrong",
                               candidate_note(search), cfg_.time_hint_tolerance_s),
                   SuspectHint::time, snap_);
  }

 private:
  std::string hint_violation(const CheckedCoarseTimeFit& checked, const Eigen::Vector3d& hint) const {
    const std::string why = implausibility(checked, cfg_);
    if (!why.empty()) return why;
    const double moved_m = (checked.fit.state.r_ecef_m - hint).norm();
    if (moved_m > cfg_.position_hint_tolerance_m)
      return fmt::format("the fix moved {} from the position hint, beyond the {} its whole milliseconds tolerate",
                         km(moved_m), km(cfg_.position_hint_tolerance_m));
    return {};
  }

  CoarseTimeFix searched_fix(const CoarseTimeSearch& search) const {
    const auto start = search.from_doppler ? CoarseTimeStart::doppler : CoarseTimeStart::grid;
    CoarseTimeFix fix = fix_from(search.fixes.front(), start, search.candidates, snap_, ctx_);
    fix.excluded_prns.insert(fix.excluded_prns.end(), search.unseen_prns.begin(), search.unseen_prns.end());
    return fix;
  }

  /// The fix from the hints failed for `why`: solve again without the position hint, then
  /// at the hinted position at other times, and say which hint is off and by how much.
  CoarseTimeFix diagnose(const Eigen::Vector3d& hint, const std::string& why) const {
    const CoarseTimeSearch search = search_without_position(snap_.satellites, snap_.dopplers, ctx_, cfg_);
    if (search.fixes.size() == 1) {
      const double off_m = (search.fixes.front().fit.state.r_ecef_m - hint).norm();
      // Within the tolerance the hint is right and only its whole milliseconds were
      // marginal: the fix found without it stands.
      if (off_m <= cfg_.position_hint_tolerance_m) return searched_fix(search);
      CoarseTimeFix fix =
          refusal(fmt::format("position hint off by {}: the code phases fit ({}) at the hinted time, {} from the hint, "
                              "more than the {} its whole milliseconds tolerate; not published (from the hint: {})",
                              km(off_m), place(search.fixes.front().fit.state.r_ecef_m), km(off_m),
                              km(cfg_.position_hint_tolerance_m), why),
                  SuspectHint::position, snap_);
      fix.position_hint_error_m = off_m;
      return fix;
    }
    const TimeScan scan = fit_at_other_times(snap_.satellites, ctx_, hint, cfg_);
    if (scan.fix) return time_verdict(*scan.fix, hint);
    return refusal(fmt::format("no fix: from the hints, {}; without the position hint, {} ({}); at the hinted "
                               "position, no time within +-{:.0f} h of the hint fits ({} tried): both hints, or the "
                               "measurements, are wrong",
                               why, search.fixes.empty() ? "no place fits" : "several places fit",
                               candidate_note(search), cfg_.time_scan_s / 3600.0, scan.steps_fitted),
                   SuspectHint::unknown, snap_);
  }

  /// The code phases fit the position hint at another time: a fix when that time is
  /// within the tolerance, else a refusal that says how far off the time hint is.
  CoarseTimeFix time_verdict(const CheckedCoarseTimeFit& fit, const Eigen::Vector3d& hint) const {
    if (hint_violation(fit, hint).empty()) return fix_from(fit, CoarseTimeStart::position_hint, 1, snap_, ctx_);
    return time_refusal(fit, "at the hinted position");
  }

  /// The code phases fit `fit`'s place (`where`) only at a time beyond the tolerance.
  CoarseTimeFix time_refusal(const CheckedCoarseTimeFit& fit, const std::string& where) const {
    const double hint_error_s = -fit.fit.state.time_correction_s;
    CoarseTimeFix refused = refusal(
        fmt::format("time hint off by {:+.0f} s: the code phases fit {} ({}) {:+.0f} s from the hinted time, more "
                    "than the +-{:.0f} s the method tolerates; not published",
                    hint_error_s, where, place(fit.fit.state.r_ecef_m), -hint_error_s, cfg_.time_hint_tolerance_s),
        SuspectHint::time, snap_);
    refused.time_hint_error_s = hint_error_s;
    return refused;
  }

  const CoarseTimeConfig& cfg_;
  Snapshot snap_;
  CoarseTimeContext ctx_;
};

}  // namespace

CoarseTimeFix CoarseTimeSolver::solve(const std::vector<SnapshotMeasurement>& measurements,
                                      const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono,
                                      const CoarseTimeHints& hints) const {
  check_snapshot_measurements(measurements);
  if (hints.position_ecef_m) check_position_hint(*hints.position_ecef_m);
  Snapshot snapshot = prepare(measurements, ephemerides, hints.time, cfg_);
  if (snapshot.satellites.size() < kMinSatellites)
    return refusal(fmt::format("{} satellites with ephemerides: a coarse-time fix needs at least {} (5 unknowns and "
                               "one to test the whole milliseconds)",
                               snapshot.satellites.size(), kMinSatellites),
                   SuspectHint::none, snapshot);
  const CoarseTimeContext context{hints.time, iono, atmosphere_, cfg_.range_errors};
  const CoarseTimeRun run(cfg_, std::move(snapshot), context);
  return hints.position_ecef_m ? run.with_position_hint(*hints.position_ecef_m) : run.without_position_hint();
}

}  // namespace deepnav
