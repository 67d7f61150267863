#pragma once
// The aided navigator fed from recordings instead of the IF receiver: GPS L1 C/A
// observations read from RINEX, broadcast ephemerides from a RINEX navigation file and an
// IMU log, coupled loosely (a PVT from the pseudoranges and Dopplers, by the receiver's PVT
// solver) or tightly (pseudorange and Doppler rows), with the same filter, INS start,
// lever arm and products as `deepnav run`.
//
// Time: one axis, GPS seconds from the start of the week of the first observation epoch.
// The observations' receiver time tags and the IMU log's times (already on GPS time, see
// ins/imu_log_reader.hpp) are both put on it.
//
// What recorded data need beyond the IF receiver's:
//  - a receiver clock re-set between epochs (rinex_obs_reader.hpp finds it) moves the
//    filter's clock bias by the same step; one too small for the reader, which the gate
//    meets as every pseudorange off by the same amount, is taken by the clock too;
//  - zero-velocity updates whenever a stationarity detector on the IMU fires (a walker
//    stops): over the last window the specific force and the angular rate each stay within
//    a tolerance of their window means, the mean specific force is gravity's magnitude, the
//    mean rate within the tolerance plus the gyro's possible bias, and the PVT's Doppler
//    speed (when there is one) is low;
//  - a satellite flagged with loss of lock keeps its pseudorange (code does not slip);
//    a satellite without Doppler gives a pseudorange row only.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aiding/aided_navigator.hpp"
#include "aiding/mode_manager.hpp"
#include "ins/imu_file.hpp"
#include "ins/imu_model.hpp"
#include "receiver/observations/carrier_smoothing.hpp"
#include "receiver/observations/rinex_obs_reader.hpp"
#include "receiver/products/product_sink.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding {

struct StationarityConfig {
  bool enabled = true;
  double window_s = 0.5;
  double accel_tolerance_mps2 = 0.25;   ///< |f - mean f| within this over the window
  double gyro_tolerance_radps = 0.25 * M_PI / 180.0;
  double velocity_sigma_mps = 0.02;     ///< of the zero-velocity update
  /// No update while the PVT's Doppler velocity is faster than this (m/s).
  double max_gnss_speed_mps = 0.5;
};

struct RecordedFusionConfig {
  NavMode mode = NavMode::tight;        ///< loose or tight
  ImuErrorModel imu;                    ///< the IMU's grade: process noise and start limits
  OscillatorNoise oscillator;
  Eigen::Vector3d lever_arm_imu_to_antenna_b_m = Eigen::Vector3d::Zero();
  PvtConfig pvt;
  AtmosphereModels atmosphere;
  double pvt_position_sigma_scale_m = 2.0;  ///< loose: position sigma = DOP x this
  double pseudorange_sigma_scale = 1.0;     ///< tight: times the shared range weight model's sigma
  /// Sigma of one pseudorange rate from a recorded Doppler: a tight row's, and in loose
  /// coupling the PVT velocity's per axis times its DOP (HDOP / sqrt 2 east and north, VDOP
  /// up), the same satellites' Dopplers through the same geometry.
  double doppler_sigma_mps = 0.1;
  /// Carrier smoothing of the pseudoranges (both modes and the PVT); off: raw code.
  bool carrier_smoothing = true;
  CarrierSmoothingConfig smoothing;
  double gate_sigma = 5.0;
  StationarityConfig stationarity;
  /// Before the first fix's ionosphere parameters (a navigation file without ION ALPHA/BETA):
  /// none are applied.
  std::optional<IonoParameters> iono;
};

/// One satellite at one epoch, as the run used it (filter.csv / innovations.csv).
struct FusionSatelliteTrace {
  int prn = 0;
  double elevation_deg = 0.0, cn0_dbhz = 0.0;
  int smoothing_epochs = 0;                      ///< 0: raw code (no smoothing), else n
  std::optional<double> code_residual_m;         ///< tight: measured minus predicted pseudorange (prior)
  std::optional<double> code_normalized;         ///< its ratio to the innovation sigma
  bool code_rejected = false;
  std::optional<double> rate_residual_mps;       ///< tight: measured minus predicted rate (prior)
  bool rate_rejected = false;
};

struct FusionEpochTrace {
  double t_s = 0.0;                              ///< since the first epoch
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
  int zero_velocity_updates = 0;         ///< applied
  int zero_velocity_rejected = 0;        ///< the detector fired, the filter's gate turned it away
  int clock_jumps_followed = 0;
  int clock_steps_absorbed = 0;          ///< every pseudorange off by one amount: the clock took it
  int filter_restarts = 0;
  int rows_rejected = 0;
  int smoothing_restarts = 0, smoothing_slips = 0, smoothing_doppler_steps = 0;
  std::string ins_start;
  std::optional<double> ins_start_t_s;  ///< seconds since the first epoch
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

/// The fusion axis: GPS seconds from the start of the first epoch's week.
double fusion_time_s(const ObservationFile& obs, const GpsTime& t);

enum class ImuTimeBase { week_seconds, gps_seconds, unix_gps };
/// "week-seconds", "gps", "unix-gps" (throws std::invalid_argument otherwise).
ImuTimeBase parse_imu_time_base(const std::string& name);
/// Moves every IMU time from `base` onto the fusion axis of `obs`.
void to_fusion_axis(ImuLog& imu, ImuTimeBase base, const ObservationFile& obs);

}  // namespace deepnav::aiding
