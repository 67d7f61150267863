#include "receiver/pvt/doppler_position.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ins/wgs84.hpp"
#include "receiver/pvt/raim.hpp"
#include "receiver/pvt/range_model.hpp"
#include "receiver/pvt/surface_grid.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kLambda_m = gps::kL1Wavelength_m;
/// A Doppler fix this far above or below the ellipsoid is a wrong branch of the
/// nonlinear problem, not a receiver (the Dopplers pin the height only to tens of km).
constexpr double kMaxAbsHeight_m = 200e3;
/// The atmosphere moves a Doppler by mm/s: nothing next to tens of Hz.
const AtmosphereModels kNoAtmosphere{IonosphereModel::none, TroposphereModel::none};

struct DopplerFit {
  bool converged = false;
  Eigen::Vector4d x = Eigen::Vector4d::Zero();  ///< position (m), drift (m/s)
  Eigen::MatrixXd H;                            ///< Hz per unknown
  Eigen::VectorXd residuals_hz;
};

/// Residuals and design matrix at `x`.
void linearise(const std::vector<DopplerSatellite>& satellites, const GpsTime& t, DopplerFit& fit) {
  const auto n = static_cast<Eigen::Index>(satellites.size());
  fit.H.resize(n, 4);
  fit.residuals_hz.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const DopplerSatellite& sat = satellites[static_cast<std::size_t>(i)];
    const RangePrediction p = predict_range(*sat.ephemeris, t, 0.0, fit.x.head<3>(), Eigen::Vector3d::Zero(),
                                            IonoParameters{}, kNoAtmosphere);
    const double rate_mps = p.pseudorange_rate_mps(Eigen::Vector3d::Zero(), fit.x(3));
    fit.residuals_hz(i) = sat.doppler_hz + rate_mps / kLambda_m;
    // d(u . v)/dx = -(v - (u . v) u) / rho for a receiver at x.
    const Eigen::Vector3d v = p.v_sat_ecef_mps;
    const Eigen::Vector3d d_rate_dx = -(v - p.los_ecef.dot(v) * p.los_ecef) / p.geometric_range_m;
    fit.H.row(i) << -d_rate_dx.transpose() / kLambda_m, -1.0 / kLambda_m;
  }
}

DopplerFit fit_from(const std::vector<DopplerSatellite>& satellites, const GpsTime& t, const Eigen::Vector3d& start,
                    int max_iterations) {
  DopplerFit fit;
  fit.x.head<3>() = start;
  for (int iter = 0; iter < max_iterations; ++iter) {
    linearise(satellites, t, fit);
    const Eigen::Matrix4d normal = fit.H.transpose() * fit.H;
    const Eigen::Vector4d step = normal.ldlt().solve(fit.H.transpose() * fit.residuals_hz);
    if (!step.allFinite()) return fit;
    fit.x += step;
    const double height = wgs84::ecef_to_llh(fit.x.head<3>()).height_m;
    if (!(std::abs(height) < kMaxAbsHeight_m)) return fit;
    if (step.head<3>().norm() < 1.0) {
      linearise(satellites, t, fit);
      fit.converged = true;
      return fit;
    }
  }
  return fit;
}

std::vector<Eigen::Vector3d> satellite_positions(const std::vector<DopplerSatellite>& satellites, const GpsTime& t) {
  std::vector<Eigen::Vector3d> positions;
  for (const auto& sat : satellites) positions.push_back(satellite_state(*sat.ephemeris, t).r_ecef_m);
  return positions;
}

DopplerPosition position_of(const DopplerFit& fit, const std::vector<DopplerSatellite>& satellites,
                            const DopplerPositionConfig& config) {
  DopplerPosition out;
  out.r_ecef_m = fit.x.head<3>();
  out.clock_drift_mps = fit.x(3);
  const double sigma2 = config.doppler_sigma_hz * config.doppler_sigma_hz;
  const Eigen::Matrix4d normal = fit.H.transpose() * fit.H;
  out.covariance_m2 = sigma2 * normal.inverse().topLeftCorner<3, 3>();
  out.dof = static_cast<int>(satellites.size()) - 4;
  out.statistic = fit.residuals_hz.squaredNorm() / sigma2;
  out.threshold = chi_square_threshold(out.dof, config.false_alarm_probability);
  out.residual_rms_hz = std::sqrt(fit.residuals_hz.squaredNorm() / static_cast<double>(satellites.size()));
  for (std::size_t k = 0; k < satellites.size(); ++k)
    out.residuals_hz[satellites[k].prn] = fit.residuals_hz(static_cast<Eigen::Index>(k));
  out.valid = out.statistic <= out.threshold;
  if (!out.valid)
    out.reason = fmt::format(
        "the Dopplers fit no static receiver at this time: weighted residuals {:.1f} > {:.1f} (RMS {:.1f} Hz against "
        "{:.1f} Hz expected)",
        out.statistic, out.threshold, out.residual_rms_hz, config.doppler_sigma_hz);
  return out;
}

}  // namespace

DopplerPosition solve_doppler_position(const std::vector<DopplerSatellite>& satellites, const GpsTime& t,
                                       const DopplerPositionConfig& config) {
  DopplerPosition out;
  if (satellites.size() < 5) {
    out.reason = fmt::format("{} Dopplers: at least 5 needed (4 unknowns and one to test them)", satellites.size());
    return out;
  }
  const std::vector<Eigen::Vector3d> starts =
      visible_surface_grid(satellite_positions(satellites, t), config.start_spacing_m, config.min_elevation_rad);
  if (starts.empty()) {
    out.reason = "no place on Earth sees all these satellites at this time";
    return out;
  }
  DopplerFit best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& start : starts) {
    const DopplerFit fit = fit_from(satellites, t, start, config.max_iterations);
    if (fit.converged && fit.residuals_hz.squaredNorm() < best_cost) {
      best_cost = fit.residuals_hz.squaredNorm();
      best = fit;
    }
  }
  if (!best.converged) {
    out.reason = fmt::format("the Doppler fit converged from none of {} starting points", starts.size());
    out.starts = static_cast<int>(starts.size());
    return out;
  }
  out = position_of(best, satellites, config);
  out.starts = static_cast<int>(starts.size());
  return out;
}

}  // namespace deepnav
