#include "aiding/delay_mismatch_detector.hpp"

#include <spdlog/spdlog.h>
#include <Eigen/Dense>
#include <cmath>

#include "signals/atmosphere.hpp"

namespace deepnav::aiding {

std::vector<RangeResidual> fix_residuals(const PvtSolution& fix, const std::map<int, double>& cn0_dbhz) {
  std::vector<RangeResidual> out;
  if (!fix.valid) return out;
  for (const SatelliteId& sat : fix.used_satellites) {
    const auto el = fix.elevation_rad.find(sat), az = fix.azimuth_rad.find(sat), res = fix.residuals_m.find(sat);
    if (el == fix.elevation_rad.end() || az == fix.azimuth_rad.end() || res == fix.residuals_m.end()) continue;
    const double ce = std::cos(el->second);
    RangeResidual r;
    r.los = Eigen::Vector3d(ce * std::sin(az->second), ce * std::cos(az->second), std::sin(el->second));  // ENU
    r.elevation_rad = el->second;
    // C/N0 is keyed by GPS PRN (the tracked channels'); other systems keep the default.
    if (const auto c = cn0_dbhz.find(sat.prn); sat.system == GnssSystem::gps && c != cn0_dbhz.end())
      r.cn0_dbhz = c->second;
    r.residual_m = res->second;
    if (const auto i = fix.ionosphere_m.find(sat); i != fix.ionosphere_m.end()) r.ionosphere_model_m = i->second;
    out.push_back(r);
  }
  return out;
}

namespace {

const char* signature_name(DelaySignature s) {
  return s == DelaySignature::troposphere_zenith ? "troposphere zenith" : "ionosphere scale";
}

/// How a model error of this kind reaches one satellite's pseudorange (see the header).
double signature_of(DelaySignature s, const RangeResidual& e) {
  return s == DelaySignature::troposphere_zenith ? troposphere_mapping(e.elevation_rad) : e.ionosphere_model_m;
}

}  // namespace

void DelayMismatchDetector::add(const std::vector<RangeResidual>& epoch, const RangeErrorModel& weights) {
  const auto n = static_cast<Eigen::Index>(epoch.size());
  const Eigen::Index nuisances = cfg_.also_fitted ? 5 : 4;
  if (n < nuisances + 2) return;  // the nuisances and the error: one redundant satellite at least
  Eigen::MatrixXd H(n, nuisances);
  Eigen::VectorXd w(n), m(n), r(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const RangeResidual& e = epoch[static_cast<std::size_t>(i)];
    H.block<1, 4>(i, 0) << e.los.transpose(), 1.0;  // position (along the line of sight) and clock
    if (cfg_.also_fitted) H(i, 4) = signature_of(*cfg_.also_fitted, e);
    w(i) = 1.0 / weights.pseudorange_variance_m2(e.elevation_rad, e.cn0_dbhz);
    m(i) = signature_of(cfg_.signature, e);
    r(i) = e.residual_m;
  }
  // e with the nuisances eliminated (Schur complement): information m' W m - b' N^-1 b and
  // right-hand side m' W r - b' N^-1 H' W r, b = H' W m.
  const Eigen::MatrixXd N = H.transpose() * w.asDiagonal() * H;
  const auto solver = N.ldlt();
  const Eigen::VectorXd b = H.transpose() * w.asDiagonal() * m;
  const Eigen::VectorXd c = H.transpose() * w.asDiagonal() * r;
  const double information = m.dot(w.cwiseProduct(m)) - b.dot(solver.solve(b));
  const double rhs = m.dot(w.cwiseProduct(r)) - b.dot(solver.solve(c));
  if (!(information > 1e-9) || !std::isfinite(information) || !std::isfinite(rhs)) return;
  if (std::abs(rhs / information) > 5.0 * std::abs(cfg_.plausible_floor)) {
    spdlog::debug("a fix's {} model error fit of {:.3f} is no model error: left out", signature_name(cfg_.signature),
                  rhs / information);
    return;
  }
  window_.push_back({information, rhs});
  spdlog::debug("{} model error fitted to one fix: {:.3f} (1-sigma {:.3f}, {} satellites)",
                signature_name(cfg_.signature), rhs / information, 1.0 / std::sqrt(information), n);
  while (static_cast<int>(window_.size()) > cfg_.window_fixes) window_.pop_front();
}

double DelayMismatchDetector::fitted_error() const {
  if (static_cast<int>(window_.size()) < cfg_.min_fixes) return 0.0;
  double information = 0.0, sum = 0.0;
  for (const FixTerm& t : window_) {
    information += t.information;
    sum += t.weighted_sum;
  }
  return sum / information;
}

double DelayMismatchDetector::consistency() const {
  const auto n = static_cast<double>(window_.size());
  if (static_cast<int>(window_.size()) < cfg_.min_fixes) return 0.0;
  double mean = 0.0;
  for (const FixTerm& t : window_) mean += t.weighted_sum / t.information / n;
  double scatter2 = 0.0;
  for (const FixTerm& t : window_) scatter2 += std::pow(t.weighted_sum / t.information - mean, 2) / (n - 1.0);
  const double fitted = fitted_error();
  if (scatter2 <= 0.0) return fitted == 0.0 ? 0.0 : std::copysign(INFINITY, fitted);
  return fitted / std::sqrt(scatter2 / n);
}

bool DelayMismatchDetector::mismatch() const {
  const double fitted = fitted_error();
  return fitted < -cfg_.threshold && fitted >= cfg_.plausible_floor && consistency() < -cfg_.min_consistency;
}

}  // namespace deepnav::aiding
