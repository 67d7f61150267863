#include "receiver/pvt/coarse_time_search.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "receiver/pvt/coarse_time_checks.hpp"
#include "receiver/pvt/snapshot_measurement.hpp"
#include "receiver/pvt/surface_grid.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kTypicalFlight_s = 0.075;
/// Two passing fixes closer than this are the same place (their sets differ only where
/// no satellite's whole milliseconds do).
constexpr double kSamePlace_m = 1e3;

/// The cheap fit's residuals beyond this RMS mark a wrong set: a wrong whole millisecond
/// leaves tens to hundreds of km, the cheap model itself (satellites moved along straight
/// lines over the time correction) a few km at two minutes.
constexpr double kScreenRms_m = 10e3;

/// A satellite's position and velocity (ECEF at the receive time) and clock, for cheap
/// predictions.
struct SatelliteSnapshot {
  Eigen::Vector3d r_ecef_m;
  Eigen::Vector3d v_ecef_mps;
  double clock_m;
};

std::vector<SatelliteSnapshot> satellites_at(const std::vector<CoarseTimeSatellite>& satellites, const GpsTime& t) {
  std::vector<SatelliteSnapshot> out;
  const GpsTime t_tx = t.plus_seconds(-kTypicalFlight_s);
  for (const auto& sat : satellites) {
    const SatelliteState s = satellite_state(*sat.ephemeris, t_tx);
    out.push_back({earth_rotation_corrected(s.r_ecef_m, kTypicalFlight_s),
                   earth_rotation_corrected(s.v_ecef_mps, kTypicalFlight_s),
                   gps::kSpeedOfLight_mps * l1_clock_correction_s(*sat.ephemeris, t_tx)});
  }
  return out;
}

WholeMilliseconds whole_ms_from(const Eigen::Vector3d& candidate, const std::vector<CoarseTimeSatellite>& satellites,
                                const std::vector<SatelliteSnapshot>& snapshots) {
  std::vector<double> submillisecond, predicted;
  std::size_t highest = 0;
  double highest_sin = -2.0;
  const Eigen::Vector3d up = candidate.normalized();  // geocentric: enough to pick the highest
  for (std::size_t k = 0; k < satellites.size(); ++k) {
    const Eigen::Vector3d d = snapshots[k].r_ecef_m - candidate;
    submillisecond.push_back(satellites[k].submillisecond_m);
    predicted.push_back(d.norm() - snapshots[k].clock_m);
    if (up.dot(d) / d.norm() > highest_sin) {
      highest_sin = up.dot(d) / d.norm();
      highest = k;
    }
  }
  return resolve_whole_milliseconds(submillisecond, predicted, highest);
}

/// Whether a set is worth a full fit: three Gauss-Newton steps of the five unknowns with
/// the cheap model from `candidate`, and the RMS of what they leave.
bool passes_screen(const Eigen::Vector3d& candidate, const WholeMilliseconds& ms,
                   const std::vector<CoarseTimeSatellite>& satellites,
                   const std::vector<SatelliteSnapshot>& snapshots) {
  using Vector5d = Eigen::Matrix<double, 5, 1>;
  const auto n = static_cast<Eigen::Index>(satellites.size());
  Vector5d x;
  x << candidate, ms.clock_bias_m, 0.0;
  Eigen::MatrixXd H(n, 5);
  Eigen::VectorXd r(n);
  for (int iter = 0; iter < 4; ++iter) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Eigen::Vector3d sat = snapshots[k].r_ecef_m + snapshots[k].v_ecef_mps * x(4);
      const Eigen::Vector3d d = sat - x.head<3>();
      const Eigen::Vector3d u = d.normalized();
      H.row(i) << -u.transpose(), 1.0, u.dot(snapshots[k].v_ecef_mps);
      const double measured = ms.milliseconds[k] * kCodePeriodRange_m + satellites[k].submillisecond_m;
      r(i) = measured - (d.norm() + x(3) - snapshots[k].clock_m);
    }
    if (iter == 3) break;
    x += (H.transpose() * H).ldlt().solve(H.transpose() * r);
  }
  return std::sqrt(r.squaredNorm() / static_cast<double>(n)) < kScreenRms_m;
}

/// The set relative to the first satellite: sets that differ by a common shift are the
/// same fix (the shift goes into the clock bias).
std::vector<int> relative_set(const WholeMilliseconds& ms) {
  std::vector<int> key = ms.milliseconds;
  for (int& m : key) m -= ms.milliseconds.front();
  return key;
}

double search_radius_m(const DopplerPosition& doppler, const CoarseTimeConfig& config) {
  const double largest_variance =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(doppler.covariance_m2).eigenvalues().maxCoeff();
  return std::clamp(3.0 * std::sqrt(std::max(largest_variance, 0.0)), config.min_doppler_search_radius_m,
                    config.max_doppler_search_radius_m);
}

void keep_if_new(std::vector<CheckedCoarseTimeFit>& fixes, CheckedCoarseTimeFit&& fit) {
  for (const auto& f : fixes)
    if ((f.fit.state.r_ecef_m - fit.fit.state.r_ecef_m).norm() < kSamePlace_m) return;
  fixes.push_back(std::move(fit));
}

/// Fits the whole-millisecond sets of candidate positions into a CoarseTimeSearch, each
/// set once.
class CandidateFitter {
 public:
  CandidateFitter(const std::vector<CoarseTimeSatellite>& satellites, const CoarseTimeContext& context,
                  const CoarseTimeConfig& config)
      : satellites_(satellites),
        snapshots_(satellites_at(satellites, context.t_hint)),
        context_(context),
        config_(config),
        no_exclusions_(config.integrity) {
    no_exclusions_.max_exclusions = 0;
  }

  /// Candidates within `radius_m` of the Doppler position; fixes beyond it are dropped.
  void around_doppler(CoarseTimeSearch& search) {
    const double radius_m = search_radius_m(*search.doppler, config_);
    const Eigen::Vector3d& centre = search.doppler->r_ecef_m;
    for (const Eigen::Vector3d& candidate : surface_grid_around(centre, radius_m, config_.grid_spacing_m))
      fit(search, candidate,
          [&](const Eigen::Vector3d& r) { return (r - centre).norm() <= radius_m + config_.grid_spacing_m; });
  }

  /// Candidates over every place that sees all the satellites; false when there is none.
  bool over_visible_region(CoarseTimeSearch& search) {
    const auto grid =
        visible_surface_grid(positions_except(satellites_.size()), config_.grid_spacing_m, config_.min_elevation_rad);
    if (grid.empty())
      search.reason = fmt::format("no place on Earth sees all {} satellites at the hinted time", satellites_.size());
    for (const Eigen::Vector3d& candidate : grid) fit(search, candidate, [](const Eigen::Vector3d&) { return true; });
    return !grid.empty();
  }

  /// The one satellite without which some place sees all the rest, if exactly one is.
  std::optional<std::size_t> unseen_satellite() const {
    std::optional<std::size_t> unseen;
    for (std::size_t k = 0; k < satellites_.size(); ++k) {
      if (visible_surface_grid(positions_except(k), config_.grid_spacing_m, config_.min_elevation_rad).empty())
        continue;
      if (unseen) return std::nullopt;  // two candidates: which one is false cannot be told
      unseen = k;
    }
    return unseen;
  }

 private:
  template <typename Within>
  void fit(CoarseTimeSearch& search, const Eigen::Vector3d& candidate, Within within) {
    const WholeMilliseconds ms = whole_ms_from(candidate, satellites_, snapshots_);
    if (!seen_.insert(relative_set(ms)).second) return;
    ++search.candidates;
    if (!passes_screen(candidate, ms, satellites_, snapshots_)) return;
    CoarseTimeState start;
    start.r_ecef_m = candidate;
    CheckedCoarseTimeFit fit = checked_coarse_time_fit(satellites_, ms, context_, start, no_exclusions_);
    if (!fit.passed || !implausible_place(fit, config_).empty() || !within(fit.fit.state.r_ecef_m)) return;
    keep_if_new(time_beyond_tolerance(fit, config_).empty() ? search.fixes : search.beyond_time_tolerance,
                std::move(fit));
  }

  /// The satellites' positions but satellite `k`'s (k = their number: all).
  std::vector<Eigen::Vector3d> positions_except(std::size_t k) const {
    std::vector<Eigen::Vector3d> positions;
    for (std::size_t i = 0; i < snapshots_.size(); ++i)
      if (i != k) positions.push_back(snapshots_[i].r_ecef_m);
    return positions;
  }

  const std::vector<CoarseTimeSatellite>& satellites_;
  const std::vector<SatelliteSnapshot> snapshots_;
  const CoarseTimeContext& context_;
  const CoarseTimeConfig& config_;
  CoarseTimeIntegrityConfig no_exclusions_;
  std::set<std::vector<int>> seen_;
};

}  // namespace

CoarseTimeSearch search_without_position(const std::vector<CoarseTimeSatellite>& satellites,
                                         const std::vector<DopplerSatellite>& dopplers,
                                         const CoarseTimeContext& context, const CoarseTimeConfig& config) {
  CoarseTimeSearch search;
  CandidateFitter fitter(satellites, context, config);
  if (dopplers.size() >= 5) {
    search.doppler = solve_doppler_position(dopplers, context.t_hint, config.doppler);
    if (search.doppler->valid) {
      search.from_doppler = true;
      fitter.around_doppler(search);
      if (!search.fixes.empty() || !search.beyond_time_tolerance.empty()) return search;
    }
  }
  // No Doppler position, or nothing fits around it (a moving receiver, a Doppler outlier,
  // a time hint far enough off to move the Doppler position): the whole visible region.
  if (static_cast<int>(satellites.size()) < config.min_grid_satellites) {
    search.too_few_satellites = search.candidates == 0;
    search.reason = fmt::format(
        "{} satellites are too few to search the Earth without a position hint (at least {}, or 5 Dopplers{})",
        satellites.size(), config.min_grid_satellites,
        search.doppler && !search.doppler->valid ? " that fit: " + search.doppler->reason : std::string());
    return search;
  }
  search.from_doppler = false;
  search.searched_visible_region = true;
  if (fitter.over_visible_region(search)) return search;
  const std::optional<std::size_t> unseen = fitter.unseen_satellite();
  if (!unseen || static_cast<int>(satellites.size()) - 1 < config.min_grid_satellites) return search;
  std::vector<CoarseTimeSatellite> rest = satellites;
  rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(*unseen));
  CandidateFitter rest_fitter(rest, context, config);
  search.unseen_prns = {satellites[*unseen].prn};
  search.reason.clear();
  rest_fitter.over_visible_region(search);
  return search;
}

}  // namespace deepnav
