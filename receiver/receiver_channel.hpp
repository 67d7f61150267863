#pragma once
// One channel of the receiver: a TrackingChannel, the controllers that close its loops, and
// the navigation data decoder its bits feed.
//
// Every channel has its own scalar loops (ScalarChannelControl). A channel an outside filter
// steers (ChannelAiding, ultra-tight) also has that filter's controller, which sees every
// epoch first: where it takes the epoch, its command acts and the scalar loops only follow,
// ready to take the channel back where the filter leaves it. A channel touches nothing but
// itself and its controllers while it tracks a block, so channels track in parallel; what
// concerns the whole receiver (ephemerides decoded, epochs to report) is handed back as
// ChannelEpochRecords.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "signals/ephemeris.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

/// Length of the carrier-phase window an observation's Doppler is averaged over.
inline constexpr double kDopplerWindow_s = 0.1;

struct ChannelObservation {
  int prn = 0;
  double pseudorange_m = 0.0;
  double doppler_hz = 0.0;
  double carrier_phase_cycles = 0.0;
  double cn0_dbhz = 0.0;
  double lock_time_s = 0.0;
  /// Samples were lost since the previous epoch: the channel coasted across the gap on its
  /// NCOs, so the carrier phase may have slipped (RINEX loss-of-lock indicator).
  bool after_gap = false;
  /// The Doppler's time minus the epoch's: it is a mean over the last kDopplerWindow_s of
  /// tracking, so it refers to the middle of that window (about -55 ms).
  double doppler_offset_s = 0.0;
  GnssSystem system = GnssSystem::gps;  ///< whose satellite `prn` numbers
  /// Galileo: observable by the lock criterion of an outside filter that steers the channel
  /// (ultra-tight), not by the channel's own C/N0 rule.
  bool aided_lock = false;

  SatelliteId satellite() const { return {system, prn}; }
};

struct ChannelSnapshot {
  int prn;
  ChannelState state;
  double cn0_dbhz;  ///< the channel's estimate, or the outside filter's (SignalLockReport) for a channel it steers
  bool has_ephemeris;
  /// Steered by an outside filter that judges the signal itself: its lock criterion
  /// (none: the channel's own loss rule applies).
  std::optional<bool> aided_lock;
};

/// What a channel's navigation data decoding achieved (for products and diagnostics).
struct NavigationStatus {
  int prn = 0;
  double tracked_s = 0.0;
  int subframes_decoded = 0;
  int parity_failures = 0;  ///< preamble candidates whose words failed parity
  bool ephemeris = false;   ///< decoded from the signal (not assisted)
};

/// How every channel tracks and closes its own loops (from ReceiverConfig).
struct ChannelLoopSettings {
  TrackingConfig tracking;
  int pll_order = 2;
  LoopBandwidths pull_in;
  LoopBandwidths tracking_loops;
};

/// One correlator epoch of a channel, kept until the whole block is tracked.
struct ChannelEpochRecord {
  CorrelatorEpoch epoch;
  ChannelSnapshot snapshot;
  bool new_ephemeris = false;  ///< the bits of this epoch completed an ephemeris
};

class ReceiverChannel {
 public:
  /// `steered`: the outside filter's controller (not owned), or nullptr; `resolution_week`:
  /// the week the decoder resolves broadcast week numbers against.
  ReceiverChannel(const ChannelLoopSettings& settings, const ChannelStart& start, ChannelController* steered,
                  int resolution_week);

  int prn() const { return tracking_->prn(); }
  const TrackingChannel& tracking() const { return *tracking_; }
  const NavDecoder& decoder() const { return *decoder_; }
  ChannelController* steered() const { return steered_; }
  void set_steered(ChannelController* steered) { steered_ = steered; }
  /// The carrier Doppler of the last epoch (the own loops' command, or the epoch's where the
  /// outside filter steered).
  double last_doppler_hz() const { return last_doppler_hz_; }

  /// Transmit time of the start of code period 0, known beforehand (a guided start).
  void seed_transmit_time(double period0_transmit_sow);
  /// Carries out what the outside filter published for the channel since it last tracked.
  /// `ephemeris`: the receiver's for the PRN, or nullptr; `clock_set`: the receiver clock is.
  void collect_published(const Ephemeris* ephemeris, bool clock_set);
  /// Tracks one block: correlation, a controller after every epoch (the outside filter's,
  /// else the own loops), the bits to the decoder; appends a record per epoch to `out`.
  void track(const SampleBlock& block, const Ephemeris* ephemeris, bool clock_set,
             std::vector<ChannelEpochRecord>& out);
  /// Whether the outside filter's lock criterion held in the block tracked since the last call.
  bool take_aided_lock();
  /// To be released after this block, whatever its state.
  void release() { released_ = true; }
  bool released() const { return released_; }
  /// Adds this channel's tracking and decoding to its PRN's status.
  void add_to(NavigationStatus& status) const;

  /// Transmit time (seconds of week) of the prompt replica at `sample`, once the decoder has it.
  std::optional<double> transmit_time_sow(std::int64_t sample) const;
  /// The channel's observables at `sample`, whose receiver time is `t_rx` and transmit time
  /// `transmit_sow`; `after_gap`: samples were lost since the previous epoch.
  ChannelObservation observe(const GpsTime& t_rx, double transmit_sow, std::int64_t sample, double sample_rate_hz,
                             bool after_gap) const;

 private:
  ChannelView view(const Ephemeris* ephemeris, bool clock_set) const;
  void carry_out(const ChannelDecision& decision);

  std::unique_ptr<TrackingChannel> tracking_;
  std::unique_ptr<ScalarChannelControl> own_loops_;
  ChannelController* steered_ = nullptr;  ///< an outside filter's controller (not owned), or none
  std::unique_ptr<NavDecoder> decoder_;
  double last_doppler_hz_ = 0.0;
  bool aided_lock_seen_ = false;  ///< the filter's lock criterion held in the block just tracked
  bool released_ = false;
};

}  // namespace deepnav
