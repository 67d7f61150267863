#pragma once
// Ultra-tight (deep) tracking: the navigation filter closes every channel's code and
// carrier loops.
//
// Measurements: each channel's integrations become discriminator values, not raw I/Q.
// The normalised early-minus-late envelope gives the code tracking error (chips); added to
// the replica's transmit time it is a pseudorange at every integration. The rate: while
// the phase loop below holds lock, the mean frequency of the channel's accumulated carrier
// phase over adjoining 100 ms windows (a delta range per window, at 10 Hz); otherwise the
// cross/dot frequency discriminator of consecutive prompts added to the NCO Doppler.
// Variances come from the channel's C/N0. Why discriminators rather
// than paper 003's [docs/references.md] E[I], E[Q] model: the I/Q model needs the signal amplitude and the
// carrier phase as extra states per channel and is linear only within a small fraction of
// a cycle, while the discriminators are amplitude-free, insensitive to data bits, linear
// over +-0.5 chip and +-25 Hz (10 ms), and enter the filter through the same pseudorange
// and rate rows as tight coupling.
//
// NCO commands: after each filter update every steered channel gets an NcoCommand from the
// filter: carrier Doppler from the predicted pseudorange rate (INS velocity, satellite
// motion, clock drift), code rate from it, and a code phase correction that puts the
// replica at the predicted transmit time. Optionally a first-order phase loop on the
// Costas error runs on top (carrier-phase tracking), which keeps the data bits readable.
// Channels are never dropped for weak signal while steered: they coast on the filter.
//
// Galileo E1 channels are steered the same way by SteeredE1Controllers (pilot integrations,
// 100 ms when weak), once the Galileo system offset is known: the filter has one clock (GPS
// time), so an E1 replica is placed at the predicted range plus that offset, and its
// discriminator pseudoranges enter less the offset, its sigma added (galileo_clock_offset.hpp).
//
// Seam: the per-channel work (discriminators, the phase loop, taking a channel over) is
// done by SteeredChannelControllers on the receiver's tracking threads; this class only
// reads what they queued and the receiver's BlockSnapshot after each block, and publishes
// the commands back into them.
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "aiding/aided_navigator.hpp"
#include "aiding/delay_mismatch_detector.hpp"
#include "aiding/steered_channel_controller.hpp"
#include "aiding/steered_e1_controller.hpp"
#include "receiver/tracking/channel_controller.hpp"

namespace deepnav::aiding {

/// The filter's side of ultra-tight tracking: one SteeredChannelController per PRN, fed
/// and read only between blocks through the receiver's BlockSnapshot.
class UltraTightTracker {
 public:
  /// `range_errors`: the pseudorange weight model shared with the PVT (its elevation terms
  /// are added to each discriminator's own noise); `faults` (may be null): satellites it
  /// excludes are measured but not used; `atmosphere`: the receiver's models (its ranges).
  UltraTightTracker(UltraTightConfig config, double sample_rate_hz, const RangeErrorModel& range_errors,
                    const SatelliteFaultMonitor* faults, const AtmosphereModels& atmosphere);

  /// The controller of the PRN's channel (made on first use, kept for the tracker's life).
  SteeredChannelController* controller_for(int prn);
  /// The same for a Galileo E1 channel.
  SteeredE1Controller* e1_controller_for(int svid);
  /// Whether the filter steers the Galileo satellite's channel now.
  bool e1_steered(int svid) const;
  /// The Galileo system offset (m) the mixed fixes estimate, and its sigma: none until
  /// known, and until then no E1 channel is taken over.
  void set_galileo_offset(std::optional<double> offset_m, double sigma_m);
  /// Which channels the controllers take over from the next block on.
  void set_engagement(Engagement engagement) { engagement_ = engagement; }

  /// The filter update with the samples the controllers queued during the block (when
  /// `measure`), then new NCO commands for the steered channels from the block's end on.
  /// The navigator must already be propagated to the block end.
  /// With `innovations`, the pseudorange rows' normalised innovations (for the fault monitor).
  KalmanUpdate update_and_steer(AidedNavigator& nav, const BlockSnapshot& block, bool measure,
                                std::vector<SatelliteInnovation>* innovations = nullptr);
  /// Where the filter predicts a satellite's signal at the block's end, for a guided search
  /// (transmit time, Doppler and its rate, their 1-sigma from the covariance); none below
  /// the elevation mask or without the receiver clock.
  std::optional<SignalPrediction> predict_signal(int prn, const Ephemeris& eph, const AidedNavigator& nav,
                                                 const BlockSnapshot& block, double elevation_mask_rad) const;
  /// Gives every channel back to its scalar loop.
  void release_all();

  /// Channels steered now, GPS and Galileo.
  int steered_channels() const;
  /// GPS channels an ultra-tight filter could take over after a block (ephemeris, transmit
  /// time, bit sync): the ones it needs to run (E1 channels join once the offset is known).
  static int count_steerable(const BlockSnapshot& block);
  /// Satellites measured within the last integration span (the longest configured length).
  int measuring_channels() const { return measuring_; }
  /// Per satellite, the mean of its discriminator pseudoranges against the filter's
  /// prediction (measured minus predicted) since the last clear (one integration's code
  /// noise is metres; a second's mean of them is what a scalar DLL would give).
  std::vector<RangeResidual> mean_pseudorange_residuals() const;
  void clear_pseudorange_residuals() { residual_sums_.clear(); }

 private:
  /// The filter's view of one satellite at an absolute sample index.
  struct SamplePrediction {
    GpsTime t_rx;               ///< receiver clock at the sample
    double offset_s = 0.0;      ///< sample time minus the navigator's time
    double clock_bias_m = 0.0;  ///< the clock model moved to the sample
    RangePrediction range;      ///< from the antenna position extrapolated to the sample
    Eigen::Vector3d antenna_velocity_ecef_mps = Eigen::Vector3d::Zero();  ///< at the sample
  };
  /// A Galileo satellite's range includes the system offset (its clock is GST's).
  std::optional<SamplePrediction> predict_at(const BroadcastEphemeris& eph, std::int64_t sample,
                                             const AidedNavigator& nav, const BlockSnapshot& block) const;
  /// The replica transmit time (seconds of week) and carrier Doppler the filter predicts there.
  static double transmit_sow(const SamplePrediction& p, const AidedNavigator& nav);
  static double doppler_hz(const SamplePrediction& p, const AidedNavigator& nav);
  std::optional<RangeMeasurement> to_measurement(const DiscriminatorSample& d, const AidedNavigator& nav,
                                                 const BlockSnapshot& block) const;
  /// Takes the samples a controller queued during the block into `ms` (or `watched`, for an
  /// excluded satellite).
  void collect(std::vector<DiscriminatorSample> samples, const AidedNavigator& nav, const BlockSnapshot& block,
               std::vector<RangeMeasurement>& ms, std::vector<RangeMeasurement>& watched);
  /// The command that puts a replica (transmit time `replica_sow`, seconds of week of its
  /// system) where the filter predicts the satellite (`predicted`, at the block's end); none
  /// when they disagree beyond max_code_correction_chips (logged once per episode).
  std::optional<NcoCommand> command_for(const SatelliteId& sat, const SamplePrediction& predicted, double replica_sow,
                                        const AidedNavigator& nav);
  /// Publishes that command into a steered channel's controller (GPS or E1), or gives the
  /// channel back when there is a prediction but they disagree.
  template <class Controller>
  void steer(const SatelliteId& sat, const std::optional<double>& replica_sow, const BroadcastEphemeris& eph,
             Controller& controller, const AidedNavigator& nav, const BlockSnapshot& block);
  UltraTightConfig cfg_;
  double fs_;
  RangeErrorModel range_errors_;
  const SatelliteFaultMonitor* faults_;
  AtmosphereModels atmosphere_;
  Engagement engagement_ = Engagement::none;
  std::map<int, SteeredChannelController> controllers_;
  std::map<int, SteeredE1Controller> e1_controllers_;
  std::optional<double> galileo_offset_m_;
  double galileo_offset_sigma_m_ = 0.0;
  bool galileo_offset_known_ = false;  ///< what the E1 controllers read
  struct ResidualSum {
    RangeResidual latest;  ///< geometry and C/N0 of the latest integration
    double sum_m = 0.0;
    int count = 0;
  };
  std::map<int, ResidualSum> residual_sums_;                  ///< GPS PRNs (the atmosphere watch's fit)
  std::map<SatelliteId, std::int64_t> last_measured_sample_;  ///< where each one's latest measurement refers to
  std::set<SatelliteId> disagreeing_;  ///< given back for disagreeing with the filter (warned once)
  int measuring_ = 0;
};

}  // namespace deepnav::aiding
