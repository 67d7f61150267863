#include "receiver/pvt/coarse_time_integrity.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "receiver/pvt/range_model.hpp"
#include "receiver/pvt/snapshot_measurement.hpp"

namespace deepnav {
namespace {

constexpr std::size_t kMinTestedSatellites = 6;  // five unknowns and one to check them

/// A fit of some of the satellites (`members`, indices into the snapshot's satellites).
struct Attempt {
  std::vector<std::size_t> members;
  CoarseTimeFit fit;
  ResidualTest test;
  bool passed = false;
};

/// The snapshot's satellites with their whole milliseconds, and the fits of subsets of them.
class SubsetFitter {
 public:
  SubsetFitter(const std::vector<CoarseTimeSatellite>& satellites, const WholeMilliseconds& ms,
               const CoarseTimeContext& context, const CoarseTimeIntegrityConfig& config)
      : satellites_(satellites), whole_ms_(ms.milliseconds), context_(context), config_(config) {}

  Attempt fit(const std::vector<std::size_t>& members, const CoarseTimeState& start) const {
    Attempt a;
    a.members = members;
    std::vector<CoarseTimeSatellite> sats;
    WholeMilliseconds ms;
    ms.clock_bias_m = start.clock_bias_m;
    for (std::size_t k : members) {
      sats.push_back(satellites_[k]);
      ms.milliseconds.push_back(whole_ms_[k]);
    }
    a.fit = fit_coarse_time(sats, ms, context_, start, config_.max_iterations);
    if (a.fit.converged && members.size() >= kMinTestedSatellites) {
      a.test = coarse_time_residual_test(a.fit, config_.false_alarm_probability);
      a.passed = !a.test.fault_detected;
    }
    return a;
  }

  /// Satellite k's whole milliseconds as the fix `state` predicts its range.
  int whole_ms_at(std::size_t k, const CoarseTimeState& state) const {
    const CoarseTimeSatellite& sat = satellites_[k];
    const RangePrediction p =
        predict_range(*sat.ephemeris, context_.t_hint.plus_seconds(state.time_correction_s), 0.0, state.r_ecef_m,
                      Eigen::Vector3d::Zero(), context_.iono, context_.atmosphere);
    return static_cast<int>(
        std::round((p.pseudorange_m(state.clock_bias_m) - sat.submillisecond_m) / kCodePeriodRange_m));
  }

  int& whole_ms(std::size_t k) { return whole_ms_[k]; }
  int prn(std::size_t k) const { return satellites_[k].prn; }

 private:
  const std::vector<CoarseTimeSatellite>& satellites_;
  std::vector<int> whole_ms_;
  const CoarseTimeContext& context_;
  const CoarseTimeIntegrityConfig& config_;
};

std::vector<std::size_t> without(std::vector<std::size_t> members, std::size_t k) {
  members.erase(std::find(members.begin(), members.end(), k));
  return members;
}

/// The member to exclude: the largest standardised residual of a converged fit; after a
/// fit that did not converge (a 300 km error can throw Gauss-Newton off), the one whose
/// absence leaves the best-fitting rest.
std::size_t member_to_exclude(const SubsetFitter& fitter, const Attempt& a, const CoarseTimeState& start) {
  if (a.fit.converged && a.test.worst_row >= 0) return a.members[static_cast<std::size_t>(a.test.worst_row)];
  std::size_t best = a.members.front();
  double best_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t k : a.members) {
    const Attempt rest = fitter.fit(without(a.members, k), start);
    if (!rest.fit.converged || rest.test.dof == 0) continue;
    const double ratio = rest.test.statistic / rest.test.threshold;
    if (ratio < best_ratio) {
      best_ratio = ratio;
      best = k;
    }
  }
  return best;
}

std::string failure_reason(const Attempt& a, std::size_t exclusions, int max_exclusions) {
  if (!a.fit.converged) return "the fit " + a.fit.reason;
  if (a.test.dof == 0)
    return fmt::format("{} satellites leave no redundancy to test the whole milliseconds (at least {} needed)",
                       a.members.size(), kMinTestedSatellites);
  const std::string why = a.test.dof == 1 ? "one degree of freedom cannot tell which satellite is wrong"
                          : exclusions >= static_cast<std::size_t>(max_exclusions)
                              ? fmt::format("{} exclusion(s) allowed", max_exclusions)
                              : std::string("too few satellites to exclude one and test again");
  return fmt::format(
      "residual test failed (weighted residuals {:.1f} > {:.1f} with {} satellites) and not repaired: {}",
      a.test.statistic, a.test.threshold, a.members.size(), why);
}

/// Puts each excluded satellite back, with the whole milliseconds the passing fix `a`
/// gives it, when the fit with it still passes (then `a` becomes that fit); records the
/// repaired and the still excluded in `out`.
void restore_excluded(SubsetFitter& fitter, Attempt& a, const std::vector<std::size_t>& excluded,
                      CheckedCoarseTimeFit& out) {
  for (std::size_t k : excluded) {
    const int before = fitter.whole_ms(k);
    fitter.whole_ms(k) = fitter.whole_ms_at(k, a.fit.state);
    std::vector<std::size_t> with = a.members;
    with.push_back(k);
    std::sort(with.begin(), with.end());
    Attempt back = fitter.fit(with, a.fit.state);
    if (back.passed) {
      a = std::move(back);
      if (fitter.whole_ms(k) != before) out.repaired_ms[fitter.prn(k)] = fitter.whole_ms(k) - before;
    } else {
      fitter.whole_ms(k) = before;
      out.excluded_prns.push_back(fitter.prn(k));
    }
  }
}

}  // namespace

ResidualTest coarse_time_residual_test(const CoarseTimeFit& fit, double false_alarm_probability) {
  const Eigen::Index n = fit.H.rows(), m = fit.H.cols();
  if (n <= m || fit.w.size() != n || fit.residuals_m.size() != n)
    throw std::invalid_argument("coarse_time_residual_test: needs more rows than unknowns in H, w and residuals");
  ResidualTest t;
  t.dof = static_cast<int>(n - m);
  t.statistic = fit.residuals_m.dot(fit.w.asDiagonal() * fit.residuals_m);
  t.threshold = chi_square_threshold(t.dof, false_alarm_probability);
  t.fault_detected = t.statistic > t.threshold;
  // Standardised residuals with C_r,ii = sigma_i^2 - h_i (H'WH)^-1 h_i' (raim.cpp).
  const Eigen::MatrixXd normal = fit.H.transpose() * fit.w.asDiagonal() * fit.H;
  const Eigen::MatrixXd NiHt = normal.ldlt().solve(fit.H.transpose());
  t.standardised.resize(n);
  double worst = -1.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double var = std::max(1.0 / fit.w(i) - fit.H.row(i).dot(NiHt.col(i)), 1e-12 / fit.w(i));
    t.standardised(i) = fit.residuals_m(i) / std::sqrt(var);
    if (std::abs(t.standardised(i)) > worst) {
      worst = std::abs(t.standardised(i));
      t.worst_row = i;
    }
  }
  return t;
}

CheckedCoarseTimeFit checked_coarse_time_fit(const std::vector<CoarseTimeSatellite>& satellites,
                                             const WholeMilliseconds& ms, const CoarseTimeContext& context,
                                             const CoarseTimeState& start_state,
                                             const CoarseTimeIntegrityConfig& config) {
  SubsetFitter fitter(satellites, ms, context, config);
  CoarseTimeState start = start_state;
  start.clock_bias_m = ms.clock_bias_m;
  std::vector<std::size_t> members(satellites.size());
  for (std::size_t k = 0; k < members.size(); ++k) members[k] = k;
  std::vector<std::size_t> excluded;
  Attempt a = fitter.fit(members, start);
  while (!a.passed) {
    const bool can_exclude = static_cast<int>(excluded.size()) < config.max_exclusions &&
                             a.members.size() > kMinTestedSatellites && (!a.fit.converged || a.test.dof > 1);
    if (!can_exclude) break;
    const std::size_t k = member_to_exclude(fitter, a, start);
    excluded.push_back(k);
    a = fitter.fit(without(a.members, k), start);
  }
  CheckedCoarseTimeFit out;
  if (a.passed) {
    restore_excluded(fitter, a, excluded, out);
  } else {
    out.reason = failure_reason(a, excluded.size(), config.max_exclusions);
    for (std::size_t k : excluded) out.excluded_prns.push_back(fitter.prn(k));
  }
  out.passed = a.passed;
  out.fit = std::move(a.fit);
  out.test = a.test;
  for (std::size_t k : a.members) {
    out.used.push_back(satellites[k]);
    out.whole_ms.push_back(fitter.whole_ms(k));
  }
  return out;
}

}  // namespace deepnav
