#pragma once
// The seam between a Galileo E1 channel and an outside filter that steers it (ultra-tight):
// the E1 counterpart of ChannelController (channel_controller.hpp). The channel's own loops
// are E1LoopController; an E1ChannelController, obtained from the run's ChannelAiding, may
// take an integration over instead (owns_epoch), and then the loops only follow the NCO so
// they can take the channel back where the filter leaves it. As for GPS, controllers read
// their channel through a read-only view and answer with decisions the channel carries
// out, so steered channels still track in parallel.
//
// What E1 adds to the GPS decision: the pilot carries no data, so a steered channel can
// integrate coherently far beyond a data symbol; the controller chooses the length
// (coherent_periods) from the signal it sees.
#include <optional>

#include "receiver/navdata/inav_navigation.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "receiver/tracking/e1_tracking_channel.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"

namespace deepnav {

/// What an E1 controller may read of its channel, and of the receiver for it.
struct E1ChannelView {
  const E1TrackingChannel& channel;
  const InavDecoder& decoder;
  const galileo::GalileoEphemeris* ephemeris = nullptr;  ///< the receiver's (decoded or assisted), or none
  bool receiver_clock_set = false;
};

/// What an E1 controller asks of its channel.
struct E1ChannelDecision {
  bool owns_epoch = false;               ///< on_epoch: this controller took the integration
  std::optional<NcoCommand> command;     ///< NCO rates (and phase jumps) from the next sample on
  std::optional<bool> loss_detection;    ///< the channel's weak-signal loss rule on or off
  std::optional<SignalLockReport> lock;  ///< on_epoch: the controller's view of the signal
  /// Pilot integrations of this many 4 ms code periods from the next one on (tracking state only).
  std::optional<int> coherent_periods;
};

class E1ChannelController {
 public:
  virtual ~E1ChannelController() = default;
  /// A completed integration of the channel (its NCOs stand at the integration's end).
  virtual E1ChannelDecision on_epoch(const E1CorrelatorEpoch& epoch, const E1ChannelView& view) = 0;
  /// Between blocks: what has been published for this channel since the last call.
  virtual E1ChannelDecision between_blocks(const E1ChannelView& view) = 0;
  /// The receiver released the channel (lost): whatever the controller keeps for it ends.
  virtual void channel_ended() {}
};

/// GST seconds of week of the prompt replica where its code phase, unwrapped from the
/// channel's start (periods * 4092 + chips), reads `code_chips`, once the I/NAV pages dated a
/// code period; none before.
std::optional<double> e1_transmit_time_sow(const InavDecoder& decoder, double code_chips);
/// The same at an integration's end, from the NCO state the epoch carries.
std::optional<double> e1_transmit_time_sow(const InavDecoder& decoder, const E1CorrelatorEpoch& epoch);

}  // namespace deepnav
