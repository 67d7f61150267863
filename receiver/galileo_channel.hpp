#pragma once
// One Galileo E1 OS channel of the receiver: an E1TrackingChannel closed by its own scalar
// loops (E1LoopController), the I/NAV decoder its E1-B symbols feed, and what the receiver
// asks of it at an observation epoch: the GST transmit time of the prompt replica and the
// observables. The counterpart of ReceiverChannel for GPS; a channel touches nothing but
// itself while it tracks a block, so channels track in parallel.
//
// Time: GST shares GPS time's second and week boundaries (GST week = GPS week - 1024) and
// differs from it by the GGTO, tens of nanoseconds: the channel reports GST seconds of week
// as they are, and the PVT's per-system clock takes up the GGTO (pvt_solver.hpp).
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/navdata/inav_navigation.hpp"
#include "receiver/receiver_channel.hpp"
#include "receiver/tracking/e1_channel_controller.hpp"
#include "receiver/tracking/e1_tracking_channel.hpp"
#include "receiver/tracking/e1_tracking_loops.hpp"

namespace deepnav {

class GalileoChannel {
 public:
  /// `steered`: an outside filter's controller for the satellite (ultra-tight), or none.
  GalileoChannel(const E1TrackingConfig& tracking, const E1LoopSettings& loops, const E1ChannelStart& start,
                 E1ChannelController* steered = nullptr);
  GalileoChannel(const GalileoChannel&) = delete;
  GalileoChannel& operator=(const GalileoChannel&) = delete;

  int svid() const { return tracking_.satellite().prn; }
  const SatelliteId& satellite() const { return tracking_.satellite(); }
  const E1TrackingChannel& tracking() const { return tracking_; }
  const InavDecoder& decoder() const { return decoder_; }

  /// Tracks one block: correlation, after every integration the outside controller (when it
  /// takes it) or the loops, the E1-B symbols to the decoder. `ephemeris` (the receiver's,
  /// or none) and `clock_set` are what the controller is shown.
  void track(const SampleBlock& block, const galileo::GalileoEphemeris* ephemeris = nullptr, bool clock_set = false);
  /// Between blocks: what the outside controller published since the channel last tracked.
  void collect_published(const galileo::GalileoEphemeris* ephemeris, bool clock_set);
  /// Whether its observables may be formed: tracking on the wiped pilot, a GST time mark
  /// decoded, and a signal behind it: while an outside filter steers the channel its lock
  /// criterion (none when it steers the channel through a fade without measuring it: the
  /// replica is then the filter's own prediction, and a fix from it would echo the filter),
  /// otherwise the C/N0 at or above `lost_cn0_dbhz`.
  bool observable(double lost_cn0_dbhz) const;
  /// The owner releases the channel: its outside controller lets it go (between blocks).
  void end();
  /// The C/N0 the channel reports: its outside controller's estimate while that one has one.
  double cn0_dbhz() const;
  /// GST seconds of week of the prompt replica at `sample`, once a time mark is decoded.
  std::optional<double> transmit_time_sow(std::int64_t sample) const;
  /// The observables at `sample`, whose receiver time is `t_rx` and GST transmit time
  /// `transmit_sow`; `after_gap`: samples were lost since the previous epoch.
  ChannelObservation observe(const GpsTime& t_rx, double transmit_sow, std::int64_t sample, double sample_rate_hz,
                             bool after_gap) const;

 private:
  /// Mean NCO Doppler over the last kDopplerWindow_s of integrations (the loop's frequency
  /// before any integration ended).
  double mean_doppler_hz() const;
  E1ChannelView view(const galileo::GalileoEphemeris* ephemeris, bool clock_set) const;
  void carry_out(const E1ChannelDecision& decision);

  struct DopplerSpan {
    std::int64_t first_sample;
    std::int64_t end_sample;
    double seconds;
    double doppler_hz;
  };
  E1TrackingChannel tracking_;
  E1LoopController loops_;
  E1ChannelController* steered_;
  bool steered_now_ = false;                    ///< the outside controller took the latest integration
  std::optional<SignalLockReport> aided_lock_;  ///< its latest verdict, while it steers and judges
  InavDecoder decoder_;
  std::deque<DopplerSpan> recent_;  ///< the latest integrations, newest last
  double tracked_s_ = 0.0;
};

}  // namespace deepnav
