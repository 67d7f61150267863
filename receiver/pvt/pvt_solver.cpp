#include "receiver/pvt/pvt_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "ins/frames.hpp"
#include "receiver/pvt/raim.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double c = gps::kSpeedOfLight_mps;

struct SatGeometry {
  Eigen::Vector3d r, v;
  double clock_m, drift_mps;
};

/// One least-squares fix with what the RAIM test needs of it: the design matrix and the
/// weights of the last iteration and the post-fit residuals, rows in used_prns' order.
struct Fit {
  PvtSolution sol;
  Eigen::MatrixXd H;
  Eigen::VectorXd w, residuals_m;
};

Fit solve_once(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
               const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono, const PvtConfig& cfg,
               const AtmosphereModels& atmosphere, const Eigen::Vector4d& seed);

std::string prn_list(const std::vector<int>& prns) {
  std::string s;
  for (int prn : prns) s += (s.empty() ? "" : ", ") + std::to_string(prn);
  return s;
}

}  // namespace

std::string to_string(RaimStatus status) {
  switch (status) {
    case RaimStatus::unavailable:
      return "unavailable";
    case RaimStatus::passed:
      return "passed";
    case RaimStatus::excluded:
      return "excluded";
    case RaimStatus::failed:
      return "failed";
  }
  return "?";
}

PvtSolution PvtSolver::solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                             const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono) {
  std::vector<PseudorangeObservation> use = obs;
  std::vector<int> excluded;
  Fit fit;
  while (true) {
    fit = solve_once(t_rx, use, ephemerides, iono, cfg_, atmosphere_, seed_);
    PvtSolution& sol = fit.sol;
    const auto n = static_cast<int>(sol.used_prns.size());
    if (!sol.valid || n < 5) {
      sol.raim = RaimStatus::unavailable;
      break;
    }
    const ResidualTest test = residual_test(fit.H, fit.w, fit.residuals_m, cfg_.raim_false_alarm_probability);
    sol.raim_statistic = test.statistic;
    sol.raim_threshold = test.threshold;
    if (!test.fault_detected) {
      sol.raim = excluded.empty() ? RaimStatus::passed : RaimStatus::excluded;
      break;
    }
    // Exclude only while the test can still run on the rest (5 satellites or more).
    const bool exclusions_left = static_cast<int>(excluded.size()) < cfg_.raim_max_exclusions;
    if (!exclusions_left || n - 1 < 5) {
      sol.raim = RaimStatus::failed;
      sol.valid = false;
      const std::string why = !exclusions_left
                                  ? fmt::format("{} exclusion(s) allowed{}", cfg_.raim_max_exclusions,
                                                excluded.empty() ? "" : ", excluded PRN " + prn_list(excluded))
                                  : std::string("too few satellites to exclude one and test again");
      sol.reason = fmt::format(
          "RAIM: fault detected (weighted residuals {:.1f} > {:.1f} with {} satellites) and not "
          "excluded ({}): fix not published",
          test.statistic, test.threshold, n, why);
      break;
    }
    const int worst_prn = sol.used_prns[static_cast<std::size_t>(test.worst_row)];
    excluded.push_back(worst_prn);
    use.erase(std::remove_if(use.begin(), use.end(), [&](const auto& o) { return o.prn == worst_prn; }), use.end());
  }
  PvtSolution sol = std::move(fit.sol);
  sol.excluded_prns = excluded;
  if (sol.valid) {
    seed_.head<3>() = sol.r_ecef_m;
    seed_(3) = sol.clock_bias_m;
  }
  return sol;
}

namespace {

Fit solve_once(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
               const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono, const PvtConfig& cfg,
               const AtmosphereModels& atmosphere, const Eigen::Vector4d& seed) {
  Fit fit;
  PvtSolution& sol = fit.sol;
  sol.t = t_rx;
  Eigen::Vector4d x = seed;
  std::vector<const PseudorangeObservation*> used;
  std::vector<SatGeometry> geo;
  Eigen::MatrixXd& H = fit.H;
  Eigen::VectorXd& W = fit.w;
  for (int iter = 0; iter < 10; ++iter) {
    used.clear();
    geo.clear();
    std::vector<Eigen::Vector4d> rows;
    std::vector<double> resid, weights;
    const bool have_position = x.head<3>().norm() > 6e6;
    const wgs84::Llh llh = have_position ? wgs84::ecef_to_llh(x.head<3>()) : wgs84::Llh{};
    for (const auto& o : obs) {
      const auto it = ephemerides.find(o.prn);
      if (it == ephemerides.end()) continue;
      const Ephemeris& eph = it->second;
      const GpsTime t_tx = t_rx.plus_seconds(-o.pseudorange_m / c);
      // Satellite clock first, so the orbit is evaluated at the true transmit time.
      const double dts = l1_clock_correction_s(eph, t_tx);
      const SatelliteState s = satellite_state(eph, t_tx.plus_seconds(-dts));
      const double tau = (s.r_ecef_m - x.head<3>()).norm() / c;
      SatGeometry g{earth_rotation_corrected(s.r_ecef_m, tau), earth_rotation_corrected(s.v_ecef_mps, tau), c * dts,
                    c * s.clock_drift_sps};
      const Eigen::Vector3d d = g.r - x.head<3>();
      const double range = d.norm();
      double el = M_PI / 2, az = 0.0, corr = 0.0;
      if (have_position) {
        const LookAngles la = look_angles(llh, x.head<3>(), g.r);
        el = la.elevation_rad;
        az = la.azimuth_rad;
        if (el < cfg.elevation_mask_rad) continue;
        corr += atmosphere.ionosphere_delay_m(iono, llh.lat_rad, llh.lon_rad, az, el, t_rx.sow);
        corr += atmosphere.troposphere_delay_m(llh.lat_rad, llh.height_m, el);
      }
      rows.emplace_back(-d.x() / range, -d.y() / range, -d.z() / range, 1.0);
      resid.push_back(o.pseudorange_m - (range + x(3) - g.clock_m + corr));
      weights.push_back(1.0 / cfg.range_errors.pseudorange_variance_m2(el, o.cn0_dbhz));
      sol.elevation_rad[o.prn] = el;
      sol.azimuth_rad[o.prn] = az;
      used.push_back(&o);
      geo.push_back(g);
    }
    if (used.size() < 4) {
      sol.reason = "fewer than 4 usable satellites (" + std::to_string(used.size()) + ")";
      return fit;
    }
    const auto n = static_cast<Eigen::Index>(used.size());
    H.resize(n, 4);
    W.resize(n);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      H.row(i) = rows[static_cast<std::size_t>(i)].transpose();
      W(i) = weights[static_cast<std::size_t>(i)];
      y(i) = resid[static_cast<std::size_t>(i)];
    }
    const Eigen::Matrix4d N = H.transpose() * W.asDiagonal() * H;
    const Eigen::Vector4d dx = N.ldlt().solve(H.transpose() * W.asDiagonal() * y);
    x += dx;
    sol.iterations = iter + 1;
    if (dx.head<3>().norm() < 1e-4) break;
  }
  // Final residuals, velocity, DOPs.
  sol.r_ecef_m = x.head<3>();
  sol.clock_bias_m = x(3);
  sol.llh = wgs84::ecef_to_llh(sol.r_ecef_m);
  const auto n = static_cast<Eigen::Index>(used.size());
  Eigen::VectorXd rr(n);
  fit.residuals_m.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& o = *used[static_cast<std::size_t>(i)];
    const auto& g = geo[static_cast<std::size_t>(i)];
    const Eigen::Vector3d d = g.r - sol.r_ecef_m;
    sol.used_prns.push_back(o.prn);
    // Pseudorange residual with the final state (atmosphere as in the last iteration).
    const double el = sol.elevation_rad[o.prn];
    double corr = 0.0;
    if (atmosphere.ionosphere == IonosphereModel::klobuchar && iono.valid) {
      const LookAngles la = look_angles(sol.llh, sol.r_ecef_m, g.r);
      sol.ionosphere_m[o.prn] =
          atmosphere.ionosphere_delay_m(iono, sol.llh.lat_rad, sol.llh.lon_rad, la.azimuth_rad, el, t_rx.sow);
      corr += sol.ionosphere_m[o.prn];
    }
    corr += atmosphere.troposphere_delay_m(sol.llh.lat_rad, sol.llh.height_m, el);
    fit.residuals_m(i) = o.pseudorange_m - (d.norm() + sol.clock_bias_m - g.clock_m + corr);
    sol.residuals_m[o.prn] = fit.residuals_m(i);
    // Range rate from Doppler: -lambda fd = u.(v_sat - v) + c (drift_rx - drift_sat).
    rr(i) = -gps::kL1Wavelength_m * o.doppler_hz - d.normalized().dot(g.v) + g.drift_mps;
  }
  const Eigen::Matrix4d N = H.transpose() * W.asDiagonal() * H;
  const Eigen::Vector4d vel = N.ldlt().solve(H.transpose() * W.asDiagonal() * rr);
  sol.v_ecef_mps = vel.head<3>();
  sol.clock_drift_mps = vel(3);
  // DOPs in the local level frame.
  const Eigen::Matrix4d Q = (H.transpose() * H).inverse();
  const Eigen::Matrix3d C = C_e_n(sol.llh.lat_rad, sol.llh.lon_rad);
  const Eigen::Matrix3d Qn = C * Q.topLeftCorner<3, 3>() * C.transpose();
  sol.dops.gdop = std::sqrt(Q.trace());
  sol.dops.pdop = std::sqrt(Q.topLeftCorner<3, 3>().trace());
  sol.dops.hdop = std::sqrt(Qn(0, 0) + Qn(1, 1));
  sol.dops.vdop = std::sqrt(Qn(2, 2));
  sol.dops.tdop = std::sqrt(Q(3, 3));
  sol.valid = std::isfinite(sol.r_ecef_m.norm()) && sol.r_ecef_m.norm() > 6.0e6 && sol.r_ecef_m.norm() < 7.0e6;
  if (!sol.valid) {
    sol.reason = "solution did not converge to the Earth's surface";
  } else if (!(sol.llh.height_m >= cfg.min_height_m && sol.llh.height_m <= cfg.max_height_m)) {
    sol.valid = false;
    sol.reason = fmt::format("implausible height {:.0f} m (accepted {:.0f} to {:.0f} m)", sol.llh.height_m,
                             cfg.min_height_m, cfg.max_height_m);
  }
  return fit;
}

}  // namespace
}  // namespace deepnav
