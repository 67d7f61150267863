#include "receiver/pvt/coarse_time_fit.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include <fmt/format.h>

#include "receiver/pvt/range_model.hpp"
#include "receiver/pvt/snapshot_measurement.hpp"

namespace deepnav {
namespace {

/// A fit that leaves this shell around the Earth's centre has diverged: no receiver is
/// there, and far outside it the linearisation no longer holds.
constexpr double kMinRadius_m = 5.0e6;
constexpr double kMaxRadius_m = 8.0e6;

RangePrediction predict_at(const CoarseTimeSatellite& sat, const CoarseTimeContext& context,
                           const CoarseTimeState& state) {
  return predict_range(*sat.ephemeris, context.t_hint.plus_seconds(state.time_correction_s), 0.0, state.r_ecef_m,
                       Eigen::Vector3d::Zero(), context.iono, context.atmosphere);
}

bool plausible(const CoarseTimeState& state) {
  const double radius = state.r_ecef_m.norm();
  return std::isfinite(radius) && radius > kMinRadius_m && radius < kMaxRadius_m && std::isfinite(state.clock_bias_m) &&
         std::isfinite(state.time_correction_s);
}

}  // namespace

WholeMilliseconds resolve_whole_milliseconds(const std::vector<double>& submillisecond_m,
                                             const std::vector<double>& predicted_m, std::size_t reference) {
  WholeMilliseconds ms;
  ms.reference = reference;
  const double reference_whole =
      std::round((predicted_m[reference] - submillisecond_m[reference]) / kCodePeriodRange_m);
  ms.clock_bias_m = reference_whole * kCodePeriodRange_m + submillisecond_m[reference] - predicted_m[reference];
  ms.milliseconds.resize(submillisecond_m.size());
  for (std::size_t k = 0; k < submillisecond_m.size(); ++k) {
    const double whole = std::round((predicted_m[k] + ms.clock_bias_m - submillisecond_m[k]) / kCodePeriodRange_m);
    ms.milliseconds[k] = static_cast<int>(whole);
  }
  return ms;
}

WholeMilliseconds resolve_whole_milliseconds(const std::vector<CoarseTimeSatellite>& satellites,
                                             const CoarseTimeContext& context, const CoarseTimeState& start) {
  std::vector<double> submillisecond(satellites.size()), predicted(satellites.size());
  std::size_t highest = 0;
  double highest_elevation = -10.0;
  for (std::size_t k = 0; k < satellites.size(); ++k) {
    const RangePrediction p = predict_at(satellites[k], context, start);
    submillisecond[k] = satellites[k].submillisecond_m;
    predicted[k] = p.pseudorange_m(0.0);
    if (p.elevation_rad > highest_elevation) {
      highest_elevation = p.elevation_rad;
      highest = k;
    }
  }
  return resolve_whole_milliseconds(submillisecond, predicted, highest);
}

CoarseTimeFit fit_coarse_time(const std::vector<CoarseTimeSatellite>& satellites, const WholeMilliseconds& ms,
                              const CoarseTimeContext& context, const CoarseTimeState& start, int max_iterations) {
  using Vector5d = Eigen::Matrix<double, 5, 1>;
  using Matrix5d = Eigen::Matrix<double, 5, 5>;
  const auto n = static_cast<Eigen::Index>(satellites.size());
  CoarseTimeFit fit;
  fit.state = start;
  fit.state.clock_bias_m = ms.clock_bias_m;
  fit.H.resize(n, 5);
  fit.w.resize(n);
  fit.residuals_m.resize(n);
  fit.pseudorange_m.resize(satellites.size());
  fit.elevation_rad.resize(satellites.size());
  for (std::size_t k = 0; k < satellites.size(); ++k)
    fit.pseudorange_m[k] = ms.milliseconds[k] * kCodePeriodRange_m + satellites[k].submillisecond_m;
  for (int iter = 1; iter <= max_iterations; ++iter) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const RangePrediction p = predict_at(satellites[k], context, fit.state);
      fit.H.row(i) << -p.los_ecef.transpose(), 1.0, p.pseudorange_rate_mps(Eigen::Vector3d::Zero(), 0.0);
      const double sigma = satellites[k].code_sigma_m;
      fit.w(i) = 1.0 / (context.range_errors.model_variance_m2(p.elevation_rad) + sigma * sigma);
      fit.residuals_m(i) = fit.pseudorange_m[k] - p.pseudorange_m(fit.state.clock_bias_m);
      fit.elevation_rad[k] = p.elevation_rad;
    }
    fit.iterations = iter;
    const Matrix5d normal = fit.H.transpose() * fit.w.asDiagonal() * fit.H;
    const Vector5d step = normal.ldlt().solve(fit.H.transpose() * fit.w.asDiagonal() * fit.residuals_m);
    // All five unknowns: a clock bias still moving means the residuals are not yet final.
    const bool settled = step.head<3>().norm() < 1e-3 && std::abs(step(3)) < 1e-3 && std::abs(step(4)) < 1e-6;
    if (settled) {
      fit.converged = true;  // the residuals above belong to this state to well below a millimetre
      return fit;
    }
    fit.state.r_ecef_m += step.head<3>();
    fit.state.clock_bias_m += step(3);
    fit.state.time_correction_s += step(4);
    if (!plausible(fit.state)) {
      fit.reason = fmt::format("diverged after {} iterations (position {:.0f} km from the Earth's centre)", iter,
                               fit.state.r_ecef_m.norm() / 1e3);
      return fit;
    }
  }
  fit.reason = fmt::format("did not settle in {} iterations", max_iterations);
  return fit;
}

}  // namespace deepnav
