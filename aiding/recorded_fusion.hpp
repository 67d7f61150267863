#pragma once
// The aided navigator fed from recordings instead of the IF receiver: GPS L1 C/A
// observations read from RINEX, broadcast ephemerides from a RINEX navigation file and an
// IMU log, coupled loosely (a PVT from the pseudoranges and Dopplers, by the receiver's PVT
// solver) or tightly (pseudorange and Doppler rows), through the same coupling steps as
// `deepnav run` (gnss_coupling.hpp: INS start, loose and tight update), with the same
// filter, lever arm and products.
//
// Time: the fusion axis (fusion_time_axis.hpp), GPS seconds of the first epoch's week.
// RINEX gives every observable of an epoch one time, the epoch's tag (the receiver's time
// of measurement): a recorded Doppler is taken at the tag, its offset 0, unless the
// receiver is known to write a mean over a window before the tag (doppler_time_offset_s;
// the IF receiver's own obs.rnx carries its 100 ms means, about -55 ms).
//
// What recorded data need beyond the IF receiver's:
//  - a receiver clock re-set between epochs (rinex_obs_reader.hpp finds it) moves the
//    filter's clock bias by the same step; one too small for the reader, which the gate
//    meets as every pseudorange off by the same amount, is taken by the clock too;
//  - zero-velocity updates whenever a stationarity detector on the IMU fires (a walker
//    stops; stationarity_detector.hpp) and the PVT's Doppler speed (when there is one) is
//    low;
//  - a satellite flagged with loss of lock keeps its pseudorange (code does not slip);
//    a satellite without Doppler gives a pseudorange row only;
//  - an IMU log with gaps, or one that ends before the observations: the INS stops where it
//    has no data, as in `deepnav run` (imu_feed.hpp), and those epochs publish the single
//    point, labelled so ("scalar"); after a gap the INS starts again from the fixes;
//  - tight: a filter whose gate turns away too many range rows (innovation_monitor.hpp:
//    more than a fifth over 3 s) no longer agrees with the observations (a Doppler or
//    pseudorange sigma far below the data's noise, a wrong lever arm) and restarts from
//    the next fix, as in `deepnav run`.
// What it does not have: the IF path's watch for atmosphere models the signal does not
// match (TroposphereResidualConfig::enable_on_mismatch and the ionosphere's are not read
// here: a residual state is estimated from the start when enabled, else never), its
// per-satellite fault exclusion.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aiding/fusion_time_axis.hpp"
#include "aiding/gnss_coupling.hpp"
#include "aiding/mode_manager.hpp"
#include "aiding/stationarity_detector.hpp"
#include "ins/imu_file.hpp"
#include "receiver/observations/carrier_smoothing.hpp"
#include "receiver/observations/rinex_obs_reader.hpp"
#include "receiver/products/product_sink.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding {

struct RecordedFusionConfig {
  NavMode mode = NavMode::tight;  ///< loose or tight
  /// The IMU, lever arm, gate and atmosphere (the PVT solver's models and the filter's
  /// residual states): the settings `deepnav run` couples with.
  CouplingSettings coupling;
  PvtConfig pvt;
  double pseudorange_sigma_scale = 1.0;  ///< tight: times the shared range weight model's sigma
  /// Sigma of one pseudorange rate from a recorded Doppler: a tight row's, and in loose
  /// coupling the PVT velocity's per axis times its DOP (HDOP / sqrt 2 east and north, VDOP
  /// up), the same satellites' Dopplers through the same geometry.
  double doppler_sigma_mps = 0.1;
  /// The recorded Dopplers' time minus their epoch's time tag: 0 as RINEX defines them;
  /// negative for a receiver that writes a mean over a window ending at the tag (minus half
  /// the window).
  double doppler_time_offset_s = 0.0;
  /// Carrier smoothing of the pseudoranges (both modes and the PVT); off: raw code.
  bool carrier_smoothing = true;
  CarrierSmoothingConfig smoothing;
  StationarityConfig stationarity;
  /// Before the first fix's ionosphere parameters (a navigation file without ION ALPHA/BETA):
  /// none are applied.
  std::optional<IonoParameters> iono;
};

/// One satellite at one epoch, as the run used it (filter.csv / innovations.csv).
struct FusionSatelliteTrace {
  int prn = 0;
  double elevation_deg = 0.0, cn0_dbhz = 0.0;
  int smoothing_epochs = 0;               ///< 0: raw code (no smoothing), else n
  std::optional<double> code_residual_m;  ///< tight: measured minus predicted pseudorange (prior)
  std::optional<double> code_normalized;  ///< its ratio to the innovation sigma
  bool code_rejected = false;
  std::optional<double> rate_residual_mps;  ///< tight: measured minus predicted rate (prior)
  bool rate_rejected = false;
};

struct FusionEpochTrace {
  double t_s = 0.0;  ///< since the first epoch
  bool filter = false;
  int pvt_satellites = 0;
  bool pvt_valid = false;
  int rows = 0, rows_rejected = 0;
  bool zero_velocity = false;
  double clock_jump_m = 0.0;
  Eigen::Vector3d position_sigma_ned_m = Eigen::Vector3d::Zero();
  std::vector<FusionSatelliteTrace> satellites;
};

/// What the run did, for summary.json.
struct RecordedFusionReport {
  int epochs = 0, fixes = 0, filter_epochs = 0;
  int zero_velocity_updates = 0;   ///< applied
  int zero_velocity_rejected = 0;  ///< the detector fired, the filter's gate turned it away
  int clock_jumps_followed = 0;
  int clock_steps_absorbed = 0;  ///< every pseudorange off by one amount: the clock took it
  int filter_restarts = 0;
  int rows_rejected = 0;
  int smoothing_restarts = 0, smoothing_slips = 0, smoothing_doppler_steps = 0;
  std::string ins_start;
  std::optional<double> ins_start_t_s;  ///< seconds since the first epoch
  int imu_gap_stops = 0;                ///< IMU gaps the INS stopped at (imu_feed.hpp)
  std::optional<double>
      imu_end_t_s;  ///< the IMU log's end, when the observations go on (seconds since the first epoch)
  std::map<std::string, double> seconds_in_mode;
  nlohmann::json json() const;
};

class RecordedFusion {
 public:
  /// `imu` times must be on the fusion's axis already (to_fusion_axis). Throws
  /// std::invalid_argument when the IMU log does not overlap the observations.
  RecordedFusion(RecordedFusionConfig config, const ObservationFile& obs, const NavData& nav, ImuLog imu);
  /// Every epoch to every sink, then finish() on each (nav: passed through).
  void run(const std::vector<ProductSink*>& sinks);
  /// Called after every epoch with what the filter did (diagnostics).
  void set_trace(std::function<void(const FusionEpochTrace&)> trace) { trace_ = std::move(trace); }
  const RecordedFusionReport& report() const { return report_; }

 private:
  RecordedFusionConfig cfg_;
  const ObservationFile& obs_;
  const NavData& nav_;
  ImuLog imu_;
  RecordedFusionReport report_;
  std::function<void(const FusionEpochTrace&)> trace_;
};

}  // namespace deepnav::aiding
