#pragma once
// The one-way seam between a tracking channel and what closes its loops.
//
// A channel emits CorrelatorEpochs and applies NcoCommands; a ChannelController turns the
// first into the second. Controllers see their channel only through a read-only
// ChannelView and answer with a ChannelDecision that the receiver carries out, so no
// controller holds or mutates a channel, and channels (each with its controllers) can
// run on different threads within a block.
//
// Two implementations: ScalarChannelControl (the channel's own PLL/FLL/DLL loops, below)
// and the INS-steered controller of the aiding layer (aiding/steered_channel_controller),
// which the receiver obtains from a ChannelAiding. Between blocks the receiver hands the
// aiding side a read-only BlockSnapshot of every channel; the aiding side publishes
// its commands into its own controllers, which the receiver collects with
// between_blocks() before the next sample is tracked.
#include <cstdint>
#include <optional>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/acquisition/guided_search.hpp"
#include "receiver/tracking/e1_tracking_types.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "receiver/tracking/tracking_types.hpp"
#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

class NavDecoder;
class E1ChannelController;

/// What a controller may read of its channel, and of the receiver for it.
struct ChannelView {
  const TrackingChannel& channel;
  const NavDecoder& decoder;
  const Ephemeris* ephemeris = nullptr;  ///< the receiver's ephemeris of the PRN (decoded or assisted), or none
  bool receiver_clock_set = false;       ///< the receiver clock is set (four transmit times seen)
};

/// A controller's own judgement of its channel's signal, where its integrations differ from
/// the channel's (long, data-wiped ones): what products and benchmarks report for it.
struct SignalLockReport {
  double cn0_dbhz = 0.0;  ///< the controller's estimate
  bool locked = false;    ///< its lock criterion holds (for the aided modes: a measurement within the last second)
};

/// What a controller asks of its channel.
struct ChannelDecision {
  bool owns_epoch = false;               ///< on_epoch: this controller took the epoch; the scalar loops follow it
  std::optional<NcoCommand> command;     ///< NCO rates (and phase jumps) from the next sample on
  std::optional<bool> loss_detection;    ///< turn the channel's weak-signal loss detection on or off
  std::optional<SignalLockReport> lock;  ///< on_epoch: the controller's view of the signal (none: the channel's own)
};

class ChannelController {
 public:
  virtual ~ChannelController() = default;
  /// A completed integration of the channel (its NCOs stand at the epoch's end).
  virtual ChannelDecision on_epoch(const CorrelatorEpoch& epoch, const ChannelView& view) = 0;
  /// Between blocks (after the aiding side's after_block(), and before the next block is
  /// tracked): what has been published for this channel since the last call.
  virtual ChannelDecision between_blocks(const ChannelView& view) = 0;
  /// The receiver released the channel (lost, or a guided start not confirmed), between
  /// blocks: whatever the controller keeps for it ends with it.
  virtual void channel_ended() {}
};

/// The channel's own loops (ScalarLoopController) as a controller: the pull-in bandwidths
/// until the channel tracks, the tracking ones after.
class ScalarChannelControl final : public ChannelController {
 public:
  ScalarChannelControl(double initial_doppler_hz, int pll_order, const LoopBandwidths& pull_in,
                       const LoopBandwidths& tracking);
  ChannelDecision on_epoch(const CorrelatorEpoch& epoch, const ChannelView& view) override;
  ChannelDecision between_blocks(const ChannelView&) override { return {}; }
  /// Another controller took the epoch: restart the loops at the Doppler it left, so they
  /// can take the channel back where it was.
  void follow(const CorrelatorEpoch& epoch, const ChannelView& view);

 private:
  void select_bandwidths(const ChannelView& view);
  ScalarLoopController loop_;
  LoopBandwidths pull_in_, tracking_;
};

/// One channel as the aiding side sees it between blocks.
struct ChannelStatus {
  int prn = 0;
  ChannelState state{};
  bool bit_synced = false;            ///< data-bit edges known
  bool decoder_synchronised = false;  ///< subframe timing known
  double cn0_dbhz = 0.0;
  std::optional<double> replica_transmit_sow;  ///< transmit time of the prompt replica at the block's end
  std::optional<Ephemeris> ephemeris;          ///< the receiver's, decoded or assisted
};

/// One Galileo E1 channel as the aiding side sees it between blocks.
struct E1ChannelStatus {
  int svid = 0;
  E1ChannelState state{};
  bool time_mark = false;  ///< the I/NAV pages dated its code periods
  double cn0_dbhz = 0.0;
  std::optional<double> replica_transmit_sow;          ///< GST transmit time of the prompt replica at the block's end
  std::optional<galileo::GalileoEphemeris> ephemeris;  ///< the receiver's, decoded or assisted
};

/// The receiver clock: t_rx(s) = reference + (s - reference_sample) / fs.
struct ReceiverClockReference {
  GpsTime reference;
  std::int64_t reference_sample = 0;
  double sample_rate_hz = 0.0;
  GpsTime at(std::int64_t sample) const {
    return reference.plus_seconds(static_cast<double>(sample - reference_sample) / sample_rate_hz);
  }
};

/// The receiver after a block, read-only for the aiding side.
struct BlockSnapshot {
  std::int64_t end_sample = 0;  ///< one past the block's last sample
  double sample_rate_hz = 0.0;
  std::optional<ReceiverClockReference> clock;  ///< once the receiver clock is set
  IonoParameters iono;                          ///< decoded or assisted (invalid: none yet)
  std::vector<int> tracked_prns;           ///< channels that tracked this block, in channel order (lost ones included)
  std::vector<ChannelStatus> channels;     ///< channels that go on tracking, in channel order
  std::vector<int> tracked_galileo_svids;  ///< Galileo channels that tracked this block (lost ones included)
  std::vector<E1ChannelStatus> galileo_channels;  ///< Galileo channels that go on tracking
};

/// A satellite the receiver does not track, with the ephemeris it has for it (decoded
/// earlier or assisted).
struct UntrackedSatellite {
  int prn = 0;
  Ephemeris ephemeris;
};

/// An outside filter that steers channels (ultra-tight aiding).
class ChannelAiding {
 public:
  virtual ~ChannelAiding() = default;
  /// The controller of a channel tracking `prn` (owned by the aiding side and stable for
  /// the receiver's life), or nullptr to leave the channel to its own loops. Called when
  /// the channel starts; its on_epoch may run on a worker thread.
  virtual ChannelController* controller_for(int prn) = 0;
  /// The same for a Galileo E1 channel tracking `svid` (none by default: its own loops).
  virtual E1ChannelController* e1_controller_for(int /*svid*/) { return nullptr; }
  /// Before each block is tracked.
  virtual void before_block() = 0;
  /// After each block is tracked, on the receiver's thread.
  virtual void after_block(const BlockSnapshot& snapshot) = 0;
  /// Where the filter predicts the signals of satellites the receiver does not track, at
  /// the snapshot's end (after after_block()): the receiver searches a narrow window
  /// around each (GuidedSearch) and starts a channel there, already bit- and
  /// time-synchronised, for the filter to steer. Only satellites the filter judges in view;
  /// none when it cannot predict (the default).
  virtual std::vector<SignalPrediction> predict_untracked(const BlockSnapshot& /*snapshot*/,
                                                          const std::vector<UntrackedSatellite>& /*satellites*/) {
    return {};
  }
};

}  // namespace deepnav
