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
// than paper 003's E[I], E[Q] model: the I/Q model needs the signal amplitude and the
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
#include <map>
#include <optional>
#include <vector>

#include "aiding/aided_navigator.hpp"
#include "aiding/troposphere_mismatch_detector.hpp"
#include "receiver/scalar_receiver.hpp"

namespace deepnav::aiding {

/// Which channels the filter takes over.
enum class Engagement {
  none,        ///< scalar loops everywhere
  faded_only,  ///< only channels whose signal has faded (INS coasting through outages)
  all,         ///< ultra-tight: every channel that can be steered
};

struct UltraTightConfig {
  double min_cn0_dbhz = 18.0;               ///< weaker integrations steer but are not measurements
  double spacing_chips = 0.5;               ///< the channels' early-late spacing
  double max_code_correction_chips = 5.0;   ///< a larger jump means the channel is not where the filter thinks
  bool carrier_phase_tracking = true;
  double carrier_phase_gain = 0.25;         ///< fraction of the Costas error removed per integration
  double faded_below_dbhz = 26.0;           ///< faded_only: take a channel over below this C/N0
  double recovered_above_dbhz = 32.0;       ///< faded_only: give it back above this
};

/// One channel's discriminator outputs from one integration.
struct DiscriminatorSample {
  int prn = 0;
  std::int64_t mid_sample = 0;
  double replica_transmit_sow = 0.0;   ///< replica transmit time at mid_sample
  double code_error_chips = 0.0;       ///< signal minus replica (positive: replica lags)
  /// Phase-locked: the mean carrier frequency over the window that just closed (adjoining
  /// windows of about 100 ms); otherwise NCO Doppler plus the frequency discriminator, when
  /// the previous integration adjoins.
  std::optional<double> doppler_hz;
  std::int64_t doppler_sample = 0;     ///< where that Doppler refers to (mid-window, or the two integrations' common edge)
  double rate_window_s = 0.0;          ///< > 0: doppler_hz is a phase-based mean over this window
  double cn0_dbhz = 0.0;
  double integration_s = 0.0;
  Ephemeris ephemeris;
};

class UltraTightTracker {
 public:
  /// `range_errors`: the pseudorange weight model shared with the PVT (its elevation terms
  /// are added to each discriminator's own noise); `faults` (may be null): satellites it
  /// excludes are measured but not used.
  UltraTightTracker(ScalarReceiver& receiver, UltraTightConfig config, const RangeErrorModel& range_errors,
                    const SatelliteFaultMonitor* faults);

  /// From ExternalChannelControl::on_epoch while ultra-tight mode runs: true when the channel is
  /// steered (it then has a discriminator sample queued).
  bool on_epoch(const CorrelatorEpoch& epoch, TrackingChannel& channel, const NavDecoder& nav, Engagement engagement);
  /// The filter update with the queued samples (when `measure`), then new NCO commands for
  /// the steered channels, from the sample `end_sample` on. The navigator must already be
  /// propagated to the block end.
  /// With `innovations`, the pseudorange rows' normalised innovations (for the fault monitor).
  UpdateResult update_and_steer(AidedNavigator& nav, std::int64_t end_sample, bool measure,
                                std::vector<SatelliteInnovation>* innovations = nullptr);
  /// Gives every channel back to its scalar loop.
  void release_all();

  int steered_channels() const { return static_cast<int>(steered_.size()); }
  /// Channels an ultra-tight filter could take over now (ephemeris, transmit time, bit sync).
  int count_steerable();
  /// Channels whose last integration was strong enough to be a measurement.
  int measuring_channels() const { return measuring_; }
  /// Per satellite, the mean of its discriminator pseudoranges against the filter's
  /// prediction (measured minus predicted) since the last call (one integration's code
  /// noise is metres; a second's mean of them is what a scalar DLL would give).
  std::vector<RangeResidual> take_mean_pseudorange_residuals();

 private:
  /// The filter's view of one satellite at an absolute sample index.
  struct SamplePrediction {
    GpsTime t_rx;              ///< receiver clock at the sample
    double offset_s = 0.0;     ///< sample time minus the navigator's time
    double clock_bias_m = 0.0; ///< the clock model moved to the sample
    RangePrediction range;     ///< from the antenna position extrapolated to the sample
    Eigen::Vector3d antenna_velocity_ecef_mps = Eigen::Vector3d::Zero();  ///< at the sample
  };
  std::optional<SamplePrediction> predict_at(const Ephemeris& eph, std::int64_t sample, const AidedNavigator& nav) const;
  /// Whether the filter can take a channel over: bit edges known, not lost, transmit time and ephemeris.
  bool can_steer(bool bit_synced, const TrackingChannel& channel, const NavDecoder& nav) const;
  std::optional<RangeMeasurement> to_measurement(const DiscriminatorSample& d, const AidedNavigator& nav) const;
  void steer(TrackingChannel& channel, const NavDecoder& nav_decoder, const AidedNavigator& nav, std::int64_t sample);
  ScalarReceiver& rx_;
  UltraTightConfig cfg_;
  RangeErrorModel range_errors_;
  const SatelliteFaultMonitor* faults_;
  std::vector<DiscriminatorSample> queued_;
  struct ChannelMemory {
    std::complex<double> prompt;
    std::int64_t end_sample = 0;
    double doppler_hz = 0.0;
    double phase_correction_cycles = 0.0;  ///< pending Costas correction for the next command
    double applied_correction_cycles = 0.0;  ///< correction applied since the last integration ended
    double last_cn0_dbhz = 0.0;
    std::optional<std::int64_t> rate_window_start;  ///< integration end where the current phase window began
    double rate_window_start_cycles = 0.0;          ///< carrier phase there (NCO plus Costas error)
  };
  std::map<int, ChannelMemory> memory_;
  struct ResidualSum {
    RangeResidual latest;  ///< geometry and C/N0 of the latest integration
    double sum_m = 0.0;
    int count = 0;
  };
  std::map<int, ResidualSum> residual_sums_;
  std::map<int, bool> steered_;
  int measuring_ = 0;
};

}  // namespace deepnav::aiding
