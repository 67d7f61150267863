#include "receiver/hot_start.hpp"

#include <algorithm>
#include <utility>

#include "receiver/pvt/coarse_time_pvt.hpp"
#include "receiver/pvt/doppler_velocity.hpp"

namespace deepnav {
namespace {

/// The solver needs five unknowns and one satellite more to test the whole milliseconds;
/// with fewer the epoch is not tried (the channels are still pulling in).
constexpr std::size_t kSatellitesToTry = 6;

}  // namespace

HotStart::HotStart(HotStartHints hints, double sample_rate_hz, AtmosphereModels atmosphere, CoarseTimeConfig config)
    : hints_(std::move(hints)), fs_(sample_rate_hz), atmosphere_(atmosphere), solver_(config, atmosphere) {}

GpsTime HotStart::time_hint_at(std::int64_t sample) const {
  if (last_) return last_->t.plus_seconds(static_cast<double>(sample - last_->sample) / fs_);
  return hints_.first_sample_time.plus_seconds(static_cast<double>(sample) / fs_);
}

PvtSolution HotStart::solve(const std::vector<SnapshotMeasurement>& measurements,
                            const std::map<int, Ephemeris>& ephemerides, const IonoParameters& iono,
                            std::int64_t sample) {
  std::size_t with_ephemeris = 0;
  for (const SnapshotMeasurement& m : measurements) with_ephemeris += ephemerides.count(m.prn);
  if (with_ephemeris < kSatellitesToTry) {
    PvtSolution none;
    none.reason = "hot start: fewer than 6 tracked satellites with ephemerides";
    return none;
  }
  ++report_.attempts;
  const CoarseTimeHints hints{time_hint_at(sample),
                              last_ ? std::optional<Eigen::Vector3d>(last_->r_ecef_m) : hints_.position_ecef_m};
  const CoarseTimeFix fix = solver_.solve(measurements, ephemerides, iono, hints);
  PvtSolution pvt = pvt_solution_of(fix, ephemerides);
  if (!fix.valid) {
    report_.last_refusal = fix.reason;
    pvt.reason = "hot start refused: " + fix.reason;
    return pvt;
  }
  std::map<int, double> dopplers_hz;
  for (const SnapshotMeasurement& m : measurements) {
    const bool used = std::find(fix.used_prns.begin(), fix.used_prns.end(), m.prn) != fix.used_prns.end();
    if (used && m.doppler_hz) dopplers_hz[m.prn] = *m.doppler_hz;
  }
  if (const auto v =
          velocity_from_dopplers(dopplers_hz, ephemerides, fix.receive_time, fix.r_ecef_m, iono, atmosphere_)) {
    pvt.v_ecef_mps = v->v_ecef_mps;
    pvt.clock_drift_mps = v->clock_drift_mps;
  } else {
    // A fix without its velocity would be published as standing still.
    pvt.valid = false;
    pvt.reason = "hot start: the Dopplers give no velocity";
    report_.last_refusal = pvt.reason;
    return pvt;
  }
  if (!report_.first_correction_s) {
    report_.first_correction_s = fix.coarse_time_correction_s;
    report_.first_fix_sample_s = static_cast<double>(sample) / fs_;
  }
  ++report_.fixes;
  last_ = LastFix{fix.receive_time, sample, fix.r_ecef_m};
  return pvt;
}

}  // namespace deepnav
