#include "receiver/pvt/pvt_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "ins/frames.hpp"
#include "receiver/pvt/raim.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double c = gps::kSpeedOfLight_mps;

struct Ephemerides {
  const std::map<int, Ephemeris>& gps;
  const std::map<int, galileo::GalileoEphemeris>& galileo;
};

struct SatGeometry {
  Eigen::Vector3d r, v;
  double clock_m, drift_mps;
};

/// Which systems' satellites a set of rows holds: what clocks a fix can estimate.
struct Systems {
  bool gps = false, galileo = false;
  bool both() const { return gps && galileo; }
  void add(GnssSystem s) { (s == GnssSystem::gps ? gps : galileo) = true; }
};

/// One least-squares fix with what the RAIM test needs of it: the design matrix and the
/// weights of the last iteration and the post-fit residuals, rows in used_satellites' order.
struct Fit {
  PvtSolution sol;
  Eigen::MatrixXd H;
  Eigen::VectorXd w, residuals_m;
  /// A mixed fix whose elevation mask left one system without satellites: to be solved
  /// again with the other's clock alone.
  std::optional<GnssSystem> lost_system;
};

/// Satellite position and velocity (in the ECEF frame of the receive time), clock and
/// drift at the transmit time of `o`; nullopt without an ephemeris of its satellite.
std::optional<SatGeometry> satellite_geometry(const PseudorangeObservation& o, const GpsTime& t_rx,
                                              const Eigen::Vector3d& r_rx, const Ephemerides& ephemerides) {
  const GpsTime t_tx = t_rx.plus_seconds(-o.pseudorange_m / c);
  double dts = 0.0;
  SatelliteState s;
  if (o.system == GnssSystem::gps) {
    const auto it = ephemerides.gps.find(o.prn);
    if (it == ephemerides.gps.end()) return std::nullopt;
    // Satellite clock first, so the orbit is evaluated at the true transmit time.
    dts = l1_clock_correction_s(it->second, t_tx);
    s = satellite_state(it->second, t_tx.plus_seconds(-dts));
  } else {
    const auto it = ephemerides.galileo.find(o.prn);
    if (it == ephemerides.galileo.end()) return std::nullopt;
    // The receiver's time labels taken as GST ones: the GGTO (tens of ns) moves a satellite
    // by a tenth of a millimetre, and the clock it leaves is the Galileo clock's to absorb.
    dts = galileo::e1_clock_correction_s(it->second, galileo::gst_from_gps_time(t_tx));
    s = galileo::satellite_state(it->second, galileo::gst_from_gps_time(t_tx.plus_seconds(-dts)));
  }
  const double tau = (s.r_ecef_m - r_rx).norm() / c;
  return SatGeometry{earth_rotation_corrected(s.r_ecef_m, tau), earth_rotation_corrected(s.v_ecef_mps, tau), c * dts,
                     c * s.clock_drift_sps};
}

/// kStates 4: position and one clock (one system); 5: position, the GPS clock and the
/// Galileo offset (both systems).
template <int kStates>
Fit solve_once(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs, const Ephemerides& ephemerides,
               const IonoParameters& iono, const PvtConfig& cfg, const AtmosphereModels& atmosphere,
               const Eigen::Matrix<double, kStates, 1>& seed);

std::string satellite_list(const std::vector<SatelliteId>& satellites) {
  std::string s;
  for (const SatelliteId& sat : satellites)
    s += (s.empty() ? "" : ", ") + (sat.system == GnssSystem::gps ? std::to_string(sat.prn) : sat.to_string());
  return s;
}

Systems systems_with_ephemeris(const std::vector<PseudorangeObservation>& obs, const Ephemerides& ephemerides) {
  Systems systems;
  for (const auto& o : obs)
    if (o.system == GnssSystem::gps ? ephemerides.gps.count(o.prn) > 0 : ephemerides.galileo.count(o.prn) > 0)
      systems.add(o.system);
  return systems;
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

int PvtSolution::used_count(GnssSystem system) const {
  return static_cast<int>(std::count_if(used_satellites.begin(), used_satellites.end(),
                                        [&](const SatelliteId& s) { return s.system == system; }));
}

PvtSolution PvtSolver::solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                             const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono) {
  static const std::map<int, galileo::GalileoEphemeris> kNoGalileo;
  return solve(t_rx, obs, ephemerides, kNoGalileo, iono);
}

PvtSolution PvtSolver::solve(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs,
                             const std::map<int, Ephemeris>& ephemerides,
                             const std::map<int, galileo::GalileoEphemeris>& galileo_ephemerides,
                             const IonoParameters& iono) {
  const Ephemerides ephs{ephemerides, galileo_ephemerides};
  std::vector<PseudorangeObservation> use = obs;
  std::vector<SatelliteId> excluded;
  const auto fit_of = [&](std::vector<PseudorangeObservation>& rows) {
    if (systems_with_ephemeris(rows, ephs).both()) {
      Eigen::Matrix<double, 5, 1> seed;
      seed << seed_, seed_offset_m_;
      Fit f = solve_once<5>(t_rx, rows, ephs, iono, cfg_, atmosphere_, seed);
      if (!f.lost_system) return f;
      // Below the mask the other system's clock has no satellite to fix it.
      const GnssSystem lost = *f.lost_system;
      rows.erase(std::remove_if(rows.begin(), rows.end(), [&](const auto& o) { return o.system == lost; }), rows.end());
    }
    return solve_once<4>(t_rx, rows, ephs, iono, cfg_, atmosphere_, seed_);
  };
  Fit fit;
  while (true) {
    fit = fit_of(use);
    PvtSolution& sol = fit.sol;
    const auto n = static_cast<int>(sol.used_satellites.size());
    // The residual test needs one satellite more than the unknowns.
    const auto states = static_cast<int>(fit.H.cols());
    if (!sol.valid || n < states + 1) {
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
    // Exclude only while the test can still run on the rest.
    const bool exclusions_left = static_cast<int>(excluded.size()) < cfg_.raim_max_exclusions;
    if (!exclusions_left || n - 1 < states + 1) {
      sol.raim = RaimStatus::failed;
      sol.valid = false;
      const std::string why = !exclusions_left
                                  ? fmt::format("{} exclusion(s) allowed{}", cfg_.raim_max_exclusions,
                                                excluded.empty() ? "" : ", excluded PRN " + satellite_list(excluded))
                                  : std::string("too few satellites to exclude one and test again");
      sol.reason = fmt::format(
          "RAIM: fault detected (weighted residuals {:.1f} > {:.1f} with {} satellites) and not "
          "excluded ({}): fix not published",
          test.statistic, test.threshold, n, why);
      break;
    }
    const SatelliteId worst = sol.used_satellites[static_cast<std::size_t>(test.worst_row)];
    excluded.push_back(worst);
    use.erase(std::remove_if(use.begin(), use.end(), [&](const auto& o) { return o.satellite() == worst; }), use.end());
  }
  PvtSolution sol = std::move(fit.sol);
  sol.excluded_satellites = excluded;
  if (sol.valid) {
    seed_.head<3>() = sol.r_ecef_m;
    seed_(3) = sol.clock_bias_m;
    if (sol.system_offset_m) seed_offset_m_ = *sol.system_offset_m;
  }
  return sol;
}

namespace {

template <int kStates>
Fit solve_once(const GpsTime& t_rx, const std::vector<PseudorangeObservation>& obs, const Ephemerides& ephemerides,
               const IonoParameters& iono, const PvtConfig& cfg, const AtmosphereModels& atmosphere,
               const Eigen::Matrix<double, kStates, 1>& seed) {
  using State = Eigen::Matrix<double, kStates, 1>;
  using Normal = Eigen::Matrix<double, kStates, kStates>;
  // Whose clock the first clock state is: GPS's unless there are Galileo satellites only.
  const Systems systems = systems_with_ephemeris(obs, ephemerides);
  const bool galileo_only = kStates == 4 && systems.galileo && !systems.gps;
  // The clock a row sees: the first clock, plus the Galileo offset on a Galileo row of a mixed fix.
  const auto clock_row = [](const State& x, GnssSystem system) {
    if constexpr (kStates == 5) return system == GnssSystem::galileo ? x(3) + x(4) : x(3);
    return x(3);
  };
  Fit fit;
  PvtSolution& sol = fit.sol;
  sol.t = t_rx;
  sol.clock_system = galileo_only ? GnssSystem::galileo : GnssSystem::gps;
  State x = seed;
  std::vector<const PseudorangeObservation*> used;
  std::vector<SatGeometry> geo;
  Eigen::MatrixXd& H = fit.H;
  Eigen::VectorXd& W = fit.w;
  for (int iter = 0; iter < 10; ++iter) {
    used.clear();
    geo.clear();
    std::vector<State> rows;
    std::vector<double> resid, weights;
    Systems in_rows;
    const bool have_position = x.template head<3>().norm() > 6e6;
    const wgs84::Llh llh = have_position ? wgs84::ecef_to_llh(x.template head<3>()) : wgs84::Llh{};
    for (const auto& o : obs) {
      const std::optional<SatGeometry> sat = satellite_geometry(o, t_rx, x.template head<3>(), ephemerides);
      if (!sat) continue;
      const SatGeometry& g = *sat;
      const Eigen::Vector3d d = g.r - x.template head<3>();
      const double range = d.norm();
      double el = M_PI / 2, az = 0.0, corr = 0.0;
      if (have_position) {
        const LookAngles la = look_angles(llh, x.template head<3>(), g.r);
        el = la.elevation_rad;
        az = la.azimuth_rad;
        if (el < cfg.elevation_mask_rad) continue;
        corr += atmosphere.ionosphere_delay_m(iono, llh.lat_rad, llh.lon_rad, az, el, t_rx.sow);
        corr += atmosphere.troposphere_delay_m(llh.lat_rad, llh.height_m, el);
      }
      State row;
      if constexpr (kStates == 5)
        row << -d.x() / range, -d.y() / range, -d.z() / range, 1.0, o.system == GnssSystem::galileo ? 1.0 : 0.0;
      else row << -d.x() / range, -d.y() / range, -d.z() / range, 1.0;
      rows.push_back(row);
      resid.push_back(o.pseudorange_m - (range + clock_row(x, o.system) - g.clock_m + corr));
      weights.push_back(1.0 / cfg.range_errors.pseudorange_variance_m2(el, o.cn0_dbhz));
      sol.elevation_rad[o.satellite()] = el;
      sol.azimuth_rad[o.satellite()] = az;
      used.push_back(&o);
      geo.push_back(g);
      in_rows.add(o.system);
    }
    if (kStates == 5 && !in_rows.both() && !used.empty()) {
      fit.lost_system = in_rows.gps ? GnssSystem::galileo : GnssSystem::gps;
      sol.reason = "one system's satellites all below the elevation mask";
      return fit;
    }
    if (used.size() < static_cast<std::size_t>(kStates)) {
      sol.reason = kStates == 4 ? "fewer than 4 usable satellites (" + std::to_string(used.size()) + ")"
                                : "fewer than 5 usable satellites of GPS and Galileo together (" +
                                      std::to_string(used.size()) + ")";
      return fit;
    }
    const auto n = static_cast<Eigen::Index>(used.size());
    H.resize(n, kStates);
    W.resize(n);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      H.row(i) = rows[static_cast<std::size_t>(i)].transpose();
      W(i) = weights[static_cast<std::size_t>(i)];
      y(i) = resid[static_cast<std::size_t>(i)];
    }
    const Normal N = H.transpose() * W.asDiagonal() * H;
    const State dx = N.ldlt().solve(H.transpose() * W.asDiagonal() * y);
    x += dx;
    sol.iterations = iter + 1;
    if (dx.template head<3>().norm() < 1e-4) break;
  }
  // Final residuals, velocity, DOPs.
  sol.r_ecef_m = x.template head<3>();
  sol.clock_bias_m = x(3);
  if constexpr (kStates == 5) sol.system_offset_m = x(4);
  sol.llh = wgs84::ecef_to_llh(sol.r_ecef_m);
  const auto n = static_cast<Eigen::Index>(used.size());
  Eigen::VectorXd rr(n);
  fit.residuals_m.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& o = *used[static_cast<std::size_t>(i)];
    const auto& g = geo[static_cast<std::size_t>(i)];
    const SatelliteId sat = o.satellite();
    const Eigen::Vector3d d = g.r - sol.r_ecef_m;
    sol.used_satellites.push_back(sat);
    // Pseudorange residual with the final state (atmosphere as in the last iteration).
    const double el = sol.elevation_rad[sat];
    double corr = 0.0;
    if (atmosphere.ionosphere == IonosphereModel::klobuchar && iono.valid) {
      const LookAngles la = look_angles(sol.llh, sol.r_ecef_m, g.r);
      sol.ionosphere_m[sat] =
          atmosphere.ionosphere_delay_m(iono, sol.llh.lat_rad, sol.llh.lon_rad, la.azimuth_rad, el, t_rx.sow);
      corr += sol.ionosphere_m[sat];
    }
    corr += atmosphere.troposphere_delay_m(sol.llh.lat_rad, sol.llh.height_m, el);
    fit.residuals_m(i) = o.pseudorange_m - (d.norm() + clock_row(x, o.system) - g.clock_m + corr);
    sol.residuals_m[sat] = fit.residuals_m(i);
    // Range rate from Doppler: -lambda fd = u.(v_sat - v) + c (drift_rx - drift_sat); Galileo
    // E1 has L1's wavelength.
    rr(i) = -gps::kL1Wavelength_m * o.doppler_hz - d.normalized().dot(g.v) + g.drift_mps;
  }
  // One clock drift for both systems: the line-of-sight and first clock columns.
  const Eigen::MatrixXd Hv = H.leftCols(4);
  const Eigen::Matrix4d Nv = Hv.transpose() * W.asDiagonal() * Hv;
  const Eigen::Vector4d vel = Nv.ldlt().solve(Hv.transpose() * W.asDiagonal() * rr);
  sol.v_ecef_mps = vel.head<3>();
  sol.clock_drift_mps = vel(3);
  // DOPs in the local level frame.
  const Normal Q = (H.transpose() * H).inverse();
  const Eigen::Matrix3d C = C_e_n(sol.llh.lat_rad, sol.llh.lon_rad);
  const Eigen::Matrix3d Qn = C * Q.template topLeftCorner<3, 3>() * C.transpose();
  if constexpr (kStates == 4) sol.dops.gdop = std::sqrt(Q.trace());
  else sol.dops.gdop = std::sqrt(Q.template topLeftCorner<4, 4>().trace());
  sol.dops.pdop = std::sqrt(Q.template topLeftCorner<3, 3>().trace());
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
