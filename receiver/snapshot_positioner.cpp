#include "receiver/snapshot_positioner.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "receiver/pvt/range_model.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

/// How many of the highest satellites the full-width search tries for the clock drift.
constexpr std::size_t kDriftProbes = 3;

struct Candidate {
  int prn = 0;
  std::optional<double> predicted_doppler_hz;
  double elevation_rad = 0.0;
};

AcquisitionConfig acquisition_config(const SnapshotPositionerConfig& c, double centre_hz, double half_width_hz) {
  AcquisitionConfig a;
  a.sample_rate_hz = c.sample_rate_hz;
  a.if_hz = c.if_hz + centre_hz;  // the search grid is centred on the IF: moving it moves the band
  a.coherent_ms = 1;
  a.noncoherent = c.snapshot_ms;
  a.doppler_max_hz = half_width_hz;
  a.pfa = c.pfa;
  return a;
}

void check_config(const SnapshotPositionerConfig& c) {
  if (c.snapshot_ms < 1 || c.snapshot_ms > kMaxNoncoherent)
    throw std::invalid_argument(fmt::format("snapshot: length {} ms must be 1..{} ms", c.snapshot_ms, kMaxNoncoherent));
  if (!(c.doppler_margin_hz > 0.0 && c.doppler_margin_hz <= c.doppler_max_hz))
    throw std::invalid_argument(fmt::format("snapshot: Doppler margin {} Hz must be in (0, doppler_max {} Hz]",
                                            c.doppler_margin_hz, c.doppler_max_hz));
}

}  // namespace

struct SnapshotPositioner::Impl {
  SnapshotPositionerConfig cfg;
  const NavData& nav;
  std::optional<Eigen::Vector3d> hint;
  Acquisition wide;
  CodePhaseRefiner refiner;
  CoarseTimeSolver solver;
  /// The narrowed search and the band it covers (absolute Dopplers), made at the first
  /// snapshot that needs it and kept while later snapshots' bands fit inside.
  std::unique_ptr<Acquisition> narrow;
  double narrow_low_hz = 0.0, narrow_high_hz = 0.0;

  Impl(SnapshotPositionerConfig c, const NavData& n, std::optional<Eigen::Vector3d> h)
      : cfg(std::move(c)),
        nav(n),
        hint(std::move(h)),
        wide(acquisition_config(cfg, 0.0, cfg.doppler_max_hz)),
        refiner(cfg.sample_rate_hz, cfg.if_hz, cfg.refinement),
        solver(with_code_sigma(cfg), cfg.atmosphere) {}

  static CoarseTimeConfig with_code_sigma(const SnapshotPositionerConfig& c) {
    CoarseTimeConfig ct = c.coarse_time;
    ct.code_sigma_m = c.code_sigma_10ms_m * std::sqrt(10.0 / c.snapshot_ms);
    return ct;
  }

  /// The PRNs to search at `t` and the ephemerides valid then.
  std::vector<Candidate> candidates(const GpsTime& t, std::map<int, Ephemeris>& ephemerides) const {
    std::vector<Candidate> out;
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
      const Ephemeris* eph = nav.select(prn, t);
      if (eph == nullptr) continue;
      ephemerides[prn] = *eph;
      Candidate c{prn, std::nullopt, 0.0};
      if (hint) {
        const RangePrediction p = predict_range(*eph, t, 0.0, *hint, Eigen::Vector3d::Zero(), nav.iono, cfg.atmosphere);
        if (p.elevation_rad < cfg.elevation_mask_rad) continue;
        c.predicted_doppler_hz = -p.pseudorange_rate_mps(Eigen::Vector3d::Zero(), 0.0) / gps::kL1Wavelength_m;
        c.elevation_rad = p.elevation_rad;
      }
      out.push_back(c);
    }
    return out;
  }

  static std::vector<int> prns_of(const std::vector<Candidate>& cs) {
    std::vector<int> prns;
    for (const auto& c : cs) prns.push_back(c.prn);
    return prns;
  }

  /// The acquisition with a position hint: the highest satellites at full width until one
  /// is found (its Doppler less the prediction is the clock's), the rest narrowed.
  std::vector<AcquisitionResult> narrowed_search(std::span<const Sample> x, std::vector<Candidate> cs,
                                                 SnapshotResult& result) {
    std::sort(cs.begin(), cs.end(),
              [](const Candidate& a, const Candidate& b) { return a.elevation_rad > b.elevation_rad; });
    std::vector<AcquisitionResult> found;
    std::size_t probed = 0;
    std::optional<double> clock_hz;
    for (; probed < std::min(kDriftProbes, cs.size()) && !clock_hz; ++probed) {
      const AcquisitionResult r = wide.search(x, {cs[probed].prn}).front();
      found.push_back(r);
      if (r.detected) clock_hz = r.doppler_hz - *cs[probed].predicted_doppler_hz;
    }
    std::vector<Candidate> rest(cs.begin() + static_cast<std::ptrdiff_t>(probed), cs.end());
    if (rest.empty()) return found;
    if (!clock_hz) {  // none of the highest seen: the hint may be wrong, search the rest fully
      for (const auto& r : wide.search(x, prns_of(rest))) found.push_back(r);
      return found;
    }
    result.clock_doppler_hz = *clock_hz;
    double low = 1e9, high = -1e9;
    for (const auto& c : rest) {
      low = std::min(low, *c.predicted_doppler_hz + *clock_hz - cfg.doppler_margin_hz);
      high = std::max(high, *c.predicted_doppler_hz + *clock_hz + cfg.doppler_margin_hz);
    }
    if (!narrow || low < narrow_low_hz || high > narrow_high_hz) {
      narrow = std::make_unique<Acquisition>(acquisition_config(cfg, (low + high) / 2, (high - low) / 2));
      narrow_low_hz = low;
      narrow_high_hz = high;
    }
    const double centre_hz = (narrow_low_hz + narrow_high_hz) / 2;
    for (AcquisitionResult r : narrow->search(x, prns_of(rest))) {
      r.doppler_hz += centre_hz;
      found.push_back(r);
    }
    return found;
  }

  SnapshotSignal refined(std::span<const Sample> x, const AcquisitionResult& r) const {
    SnapshotSignal s{r.prn, r.code_phase_chips, r.doppler_hz, r.cn0_dbhz, false, {}, std::nullopt};
    const RefinedSignal f = refiner.refine(x, r.prn, r.code_phase_chips, r.doppler_hz);
    if (f.converged) {
      s.code_phase_chips = f.code_phase_chips;
      s.doppler_hz = f.doppler_hz;
      s.refined = true;
    } else {
      s.refinement_note = f.reason;
    }
    return s;
  }

  SnapshotResult solve(std::span<const Sample> samples, const GpsTime& t_hint) {
    const std::span<const Sample> x = samples.first(std::min(samples.size(), snapshot_samples()));
    SnapshotResult result;
    std::map<int, Ephemeris> ephemerides;
    std::vector<Candidate> cs = candidates(t_hint, ephemerides);
    result.with_ephemeris = prns_of(cs);
    std::vector<AcquisitionResult> found;
    if (ephemerides.empty()) {
      for (int prn = 1; prn <= gps::kMaxPrn; ++prn) result.searched_prns.push_back(prn);
      found = wide.search(x);
    } else {
      result.searched_prns = prns_of(cs);
      found = hint ? narrowed_search(x, cs, result) : wide.search(x, result.searched_prns);
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.prn < b.prn; });
    std::vector<SnapshotMeasurement> measurements;
    for (const AcquisitionResult& r : found) {
      if (!r.detected) continue;
      SnapshotSignal s = refined(x, r);
      for (const auto& c : cs)
        if (c.prn == s.prn) s.predicted_doppler_hz = c.predicted_doppler_hz;
      measurements.push_back({s.prn, s.code_phase_chips, s.doppler_hz, s.cn0_dbhz});
      result.signals.push_back(std::move(s));
    }
    if (ephemerides.empty()) {
      result.fix.reason = fmt::format("no ephemeris in {} is valid at the time hint (GPS week {}, {:.0f} s of week)",
                                      nav.source, t_hint.week, t_hint.sow);
      return result;
    }
    result.fix = solver.solve(measurements, ephemerides, nav.iono, {t_hint, hint});
    return result;
  }

  std::size_t snapshot_samples() const {
    return static_cast<std::size_t>(std::llround(cfg.snapshot_ms * 1e-3 * cfg.sample_rate_hz));
  }
};

SnapshotPositioner::SnapshotPositioner(SnapshotPositionerConfig config, const NavData& nav,
                                       std::optional<Eigen::Vector3d> position_hint_ecef_m) {
  check_config(config);
  impl_ = std::make_unique<Impl>(std::move(config), nav, std::move(position_hint_ecef_m));
}

SnapshotPositioner::~SnapshotPositioner() = default;

std::size_t SnapshotPositioner::snapshot_samples() const { return impl_->snapshot_samples(); }

SnapshotResult SnapshotPositioner::solve(std::span<const Sample> samples, const GpsTime& t_hint) {
  return impl_->solve(samples, t_hint);
}

}  // namespace deepnav
