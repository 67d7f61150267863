#pragma once
// A position from a snapshot of IF samples (2 to 100 ms): acquire the satellites the
// navigation data puts above the horizon, refine their code phases and Dopplers
// (receiver/acquisition/code_phase_refinement.hpp), and solve by coarse-time navigation
// (receiver/pvt/coarse_time_solver.hpp). What `deepnav snap` runs on each snapshot.
//
// Which satellites: with a position hint, those whose broadcast orbits are above the
// horizon there at the hinted time (the rest cannot be received); without one, every PRN
// with an ephemeris valid then; with no valid ephemeris, all 32 (to list what the snapshot
// holds before saying what is missing).
//
// Speed. The FFT plans and code spectra are made once per positioner (one Acquisition
// for the snapshot length), and every snapshot reuses them. With a position hint the
// search is narrowed: only the visible PRNs, and in Doppler to the band their predicted
// Dopplers span (moved by the receiver clock drift that the first, full-width search of
// the highest satellite measures) plus a margin, instead of +-doppler_max_hz.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/acquisition/acquisition.hpp"
#include "receiver/acquisition/code_phase_refinement.hpp"
#include "receiver/pvt/coarse_time_solver.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

struct SnapshotPositionerConfig {
  double sample_rate_hz = 4.092e6;
  double if_hz = 0.0;
  int snapshot_ms = 10;  ///< samples per snapshot: snapshot_ms of them (1 ms coherent blocks)
  double doppler_max_hz = 5000.0;
  /// With a position hint: the narrowed search covers the predicted Dopplers (after the
  /// measured clock drift) +- this: the hint's errors (100 km, a minute: ~100-300 Hz) and
  /// the acquisition's bin.
  double doppler_margin_hz = 700.0;
  double pfa = 1e-5;                ///< of the acquisition, per PRN
  double elevation_mask_rad = 0.0;  ///< "above the horizon" for the choice of PRNs
  /// The refined code phase's noise (1 sigma, as a range) for a 10 ms snapshot at the
  /// coarse-time fix's reference C/N0 (45 dB-Hz); it goes as 1 / sqrt(length): the
  /// early-late balance of non-coherent 1 ms blocks, sqrt(d / (2 C/N0 T)) chip with
  /// d = 0.5, is 8 m at 10 ms, and the residuals of synthesized snapshots agree. It
  /// replaces coarse_time.code_sigma_m, which would otherwise fail the residual test of
  /// short snapshots and over-weight nothing in long ones.
  double code_sigma_10ms_m = 8.0;
  CoarseTimeConfig coarse_time;
  AtmosphereModels atmosphere;
  CodePhaseRefinementConfig refinement;
};

/// One satellite the snapshot holds.
struct SnapshotSignal {
  int prn = 0;
  double code_phase_chips = 0.0;  ///< refined, at the snapshot's first sample
  double doppler_hz = 0.0;        ///< refined
  double cn0_dbhz = 0.0;          ///< the acquisition's estimate
  bool refined = false;           ///< false: the acquisition's values (refinement failed, reason given)
  std::string refinement_note;
  std::optional<double> predicted_doppler_hz;  ///< from the navigation data and the position hint
};

struct SnapshotResult {
  std::vector<int> searched_prns;
  std::vector<SnapshotSignal> signals;  ///< detected, in PRN order
  /// PRNs searched because an ephemeris is valid at the hinted time (empty: none is, and
  /// no fix can be made; every PRN was searched).
  std::vector<int> with_ephemeris;
  CoarseTimeFix fix;
  double clock_doppler_hz = 0.0;  ///< the common Doppler offset the narrowed search used
};

class SnapshotPositioner {
 public:
  /// Throws std::invalid_argument for a bad configuration (sample rate, IF, length).
  SnapshotPositioner(SnapshotPositionerConfig config, const NavData& nav,
                     std::optional<Eigen::Vector3d> position_hint_ecef_m);
  ~SnapshotPositioner();
  SnapshotPositioner(const SnapshotPositioner&) = delete;
  SnapshotPositioner& operator=(const SnapshotPositioner&) = delete;

  /// Samples in one snapshot.
  std::size_t snapshot_samples() const;

  /// The snapshot `samples` (at least one code period; snapshot_samples() used), whose
  /// first sample the receiver clock dates `t_hint` (approximately: the time hint).
  SnapshotResult solve(std::span<const Sample> samples, const GpsTime& t_hint);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepnav
