#pragma once
// The receiver with INS aiding: the scalar receiver's channels, navigation data and PVT,
// a strapdown INS fed by an IMU log, the 17-state filter coupled in the mode the user
// asks for (loose, tight or ultra-tight), and the mode manager that falls back when a
// mode cannot run. The INS starts from its own alignment once the receiver has a fix.
//
// Time: the IMU log's t_s and the IF samples share one axis, t = sample index / fs (both
// count from the start of the recording, as the synthesizer writes them).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aiding/aided_navigator.hpp"
#include "aiding/delay_mismatch_detector.hpp"
#include "aiding/mode_manager.hpp"
#include "aiding/ultra_tight_tracker.hpp"
#include "ins/imu_file.hpp"
#include "receiver/gnss_receiver.hpp"

namespace deepnav::aiding {

struct AidedReceiverConfig {
  NavMode mode = NavMode::ultra;
  ReceiverConfig receiver;
  ImuErrorModel imu;  ///< the IMU's grade: process noise and alignment limits
  OscillatorNoise oscillator;
  Eigen::Vector3d lever_arm_imu_to_antenna_b_m = Eigen::Vector3d::Zero();
  UltraTightConfig ultra;
  ModeLimits limits;
  /// Filter update rate in ultra-tight mode is the block rate (100 Hz); loose and tight
  /// update at the receiver's observation epochs.
  double pvt_position_sigma_scale_m = 2.0;  ///< loose: position sigma = DOP x this
  double pvt_velocity_sigma_mps = 0.1;
  /// Tight and ultra-tight: the zenith troposphere residual and ionosphere scale states
  /// (each taken when its model is found not to match the signal), and per-satellite fault
  /// exclusion on the pseudorange innovations (satellite_fault_monitor.hpp).
  TroposphereResidualConfig troposphere;
  IonosphereResidualConfig ionosphere;
  DelayMismatchConfig troposphere_mismatch;
  DelayMismatchConfig ionosphere_mismatch{
      .signature = DelaySignature::ionosphere_scale, .threshold = 0.75, .plausible_floor = -1.75};
  bool fault_exclusion = true;
  /// An aided or coasting solution whose own horizontal 1-sigma exceeds this (m) is not
  /// published: the INS alone after a long outage, or a filter that has lost its way, is
  /// not a fix (it still runs on and is published again once measurements bring it back).
  double max_published_sigma_m = 100.0;
  SatelliteFaultConfig faults;
};

/// The aided solution at one observation epoch, next to the receiver's own.
struct AidedEpoch {
  ReceiverEpoch receiver;  ///< observables and the receiver's standalone PVT
  /// The coupling the filter runs at this epoch (the mode manager's choice).
  NavMode coupling = NavMode::scalar;
  /// What the solution is published as: the coupling, except that a solution whose update
  /// at this epoch took fewer than kMinSatellitesForAidedLabel satellites (loose: no PVT;
  /// tight: ranges; ultra-tight: measuring channels) is labelled coast: the INS, not the
  /// satellites, carries it in the directions they leave open.
  NavMode mode = NavMode::scalar;
  bool valid = false;                                  ///< an aided (or coasting) INS solution exists
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();  ///< antenna
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  wgs84::Llh llh{};
  Eigen::Vector3d v_ned_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy_rad = Eigen::Vector3d::Zero();  ///< roll, pitch, yaw of the body
  Eigen::Vector3d position_sigma_ned_m = Eigen::Vector3d::Zero();
  double clock_bias_m = 0.0, clock_drift_mps = 0.0;
  int steered_channels = 0;
  int measuring_channels = 0;
  /// Satellites whose measurements the filter took at its last update in this mode
  /// (PVT satellites in loose mode, range rows in tight, discriminators in ultra; 0 coasting).
  int filter_satellites = 0;
};

/// Satellites an aided update must take for its solution to carry that mode's
/// label: with fewer, position and clock are not observable from the satellites alone.
inline constexpr int kMinSatellitesForAidedLabel = 4;

class AidedReceiver {
 public:
  /// Throws std::invalid_argument when the IMU log is empty or starts more than 1 s after
  /// the first sample (it cannot cover the IF data); `if_duration_s` (when known) is also
  /// checked against the log's end.
  AidedReceiver(AidedReceiverConfig config, SampleSource& source, ImuLog imu, std::optional<double> if_duration_s);
  ~AidedReceiver();

  void run(const std::function<void(const AidedEpoch&)>& on_epoch,
           const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation = {},
           const std::function<void(double)>& progress = {});

  GnssReceiver& receiver();
  const std::vector<ModeChange>& mode_changes() const;
  /// How the INS was started ("" until it was).
  const std::string& ins_start_method() const;
  /// Set when the filter failed (NaN, lost positive definiteness) and was restarted.
  int filter_restarts() const;
  /// Times a satellite was excluded by the per-satellite fault monitor.
  int satellite_exclusions() const;
  /// Epochs whose solution was withheld for its covariance (max_published_sigma_m).
  int withheld_solutions() const;
  /// What the watch for a troposphere (zenith error, m) and an ionosphere (scale error)
  /// model mismatch found, with the filter's estimate of that state now; a state on from
  /// the start is not reported here.
  DelayMismatchReport troposphere_mismatch() const;
  DelayMismatchReport ionosphere_mismatch() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepnav::aiding
