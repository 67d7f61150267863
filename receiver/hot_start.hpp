#pragma once
// Hot start by coarse-time navigation: with ephemerides given (--ephemeris-from) and an
// approximate time, a receiver fixes from its channels' code phases alone, before any
// HOW is decoded. At each observation epoch before the receiver clock is set, the code
// phase of every tracking channel (its transmit time modulo 1 ms) and its Doppler go to
// the coarse-time solver (receiver/pvt/coarse_time_solver.hpp: whole milliseconds from an
// approximate position, the time error as a fifth unknown), and the fix gets its velocity
// from the Dopplers (receiver/pvt/doppler_velocity.hpp).
//
// Hints: the time of the source's first sample (advanced by the sample count), optionally
// a position. Once a fix is made, the next epochs take that fix's time (advanced) and
// place as their hints: tighter than the user's, so a later epoch is no weaker than the
// first. A refusal (a hint off by more than the method tolerates, too few satellites) is
// kept with its reason and publishes no fix; the receiver then waits for the broadcast
// time as on a cold start.
//
// Why not seed the channels' transmit times from the fix instead: the time correction of
// a coarse-time fix is good to milliseconds at best (it is observed only through the
// satellites' range rates), and a transmit time a millisecond off puts a satellite 4 km
// along its orbit. Each epoch is therefore its own five-unknown fix until a subframe's
// HOW gives the time.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/pvt/coarse_time_solver.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "receiver/pvt/snapshot_measurement.hpp"

namespace deepnav {

struct HotStartHints {
  GpsTime first_sample_time{};  ///< approximate GPS time of the source's sample 0 (the file's first)
  std::optional<Eigen::Vector3d> position_ecef_m;
};

/// What the hot start did over a run (summary.json).
struct HotStartReport {
  int attempts = 0;  ///< epochs tried (satellites with ephemerides enough to try)
  int fixes = 0;
  std::string last_refusal;                  ///< the reason the last refused attempt gave
  std::optional<double> first_correction_s;  ///< the first fix's time correction (true - hint)
  std::optional<double> first_fix_sample_s;  ///< when the first fix was made (s since sample 0)
};

class HotStart {
 public:
  HotStart(HotStartHints hints, double sample_rate_hz, AtmosphereModels atmosphere, CoarseTimeConfig config = {});

  /// The approximate GPS time of absolute sample `sample`: the last fix's, else the hint's,
  /// advanced by the samples since.
  GpsTime time_hint_at(std::int64_t sample) const;
  /// A fix at `sample` from the channels' code phases and Dopplers there; `ephemerides` by
  /// PRN, those in use at the hinted time. Not valid (with the reason) when the solver
  /// refuses it or too few satellites have ephemerides.
  PvtSolution solve(const std::vector<SnapshotMeasurement>& measurements, const std::map<int, Ephemeris>& ephemerides,
                    const IonoParameters& iono, std::int64_t sample);
  const HotStartReport& report() const { return report_; }

 private:
  HotStartHints hints_;
  double fs_;
  AtmosphereModels atmosphere_;
  CoarseTimeSolver solver_;
  /// The last fix: its GPS time, sample and place (the next epoch's hints).
  struct LastFix {
    GpsTime t;
    std::int64_t sample;
    Eigen::Vector3d r_ecef_m;
  };
  std::optional<LastFix> last_;
  HotStartReport report_;
};

}  // namespace deepnav
