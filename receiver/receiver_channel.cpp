#include "receiver/receiver_channel.hpp"

#include "signals/gps_constants.hpp"

namespace deepnav {

ReceiverChannel::ReceiverChannel(const ChannelLoopSettings& settings, const ChannelStart& start,
                                 ChannelController* steered, int resolution_week)
    : tracking_(std::make_unique<TrackingChannel>(settings.tracking, start)),
      own_loops_(std::make_unique<ScalarChannelControl>(start.doppler_hz, settings.pll_order, settings.pull_in,
                                                        settings.tracking_loops)),
      steered_(steered),
      decoder_(std::make_unique<NavDecoder>(start.prn, resolution_week)),
      last_doppler_hz_(start.doppler_hz) {}

void ReceiverChannel::seed_transmit_time(double period0_transmit_sow) { decoder_->seed_time(0, period0_transmit_sow); }

ChannelView ReceiverChannel::view(const Ephemeris* ephemeris, bool clock_set) const {
  return ChannelView{*tracking_, *decoder_, ephemeris, clock_set};
}

void ReceiverChannel::carry_out(const ChannelDecision& decision) {
  if (decision.loss_detection) tracking_->set_loss_detection(*decision.loss_detection);
  if (decision.command) tracking_->apply(*decision.command);
}

void ReceiverChannel::collect_published(const Ephemeris* ephemeris, bool clock_set) {
  if (steered_) carry_out(steered_->between_blocks(view(ephemeris, clock_set)));
}

void ReceiverChannel::track(const SampleBlock& block, const Ephemeris* ephemeris, bool clock_set,
                            std::vector<ChannelEpochRecord>& out) {
  tracking_->process(block, [&](const CorrelatorEpoch& e) {
    const ChannelView v = view(ephemeris, clock_set);
    ChannelDecision outside;
    if (steered_) {
      outside = steered_->on_epoch(e, v);
      carry_out(outside);
    }
    if (!outside.owns_epoch) {
      // Each epoch's command acts from the very next sample (not after the block).
      const ChannelDecision own = own_loops_->on_epoch(e, v);
      carry_out(own);
      last_doppler_hz_ = own.command->carrier_doppler_hz;
    } else {
      // Keep the loops ready to take the channel back where the outside filter leaves it.
      own_loops_->follow(e, v);
      last_doppler_hz_ = e.carrier_doppler_hz;
    }
    // The channel assembles the data bits (sums over each bit's 20 code periods); a bit
    // completed by this epoch goes to the decoder at once.
    bool fresh = false;
    for (const PromptBit& bit : tracking_->take_bits()) fresh = decoder_->add_bit(bit) || fresh;
    ChannelSnapshot snap{prn(), tracking_->state(), tracking_->cn0_dbhz(), decoder_->ephemeris().has_value(), {}};
    if (outside.owns_epoch && outside.lock) {
      snap.cn0_dbhz = outside.lock->cn0_dbhz;
      snap.aided_lock = outside.lock->locked;
      aided_lock_seen_ = aided_lock_seen_ || outside.lock->locked;
    }
    out.push_back({e, snap, fresh});
  });
}

bool ReceiverChannel::take_aided_lock() {
  const bool locked = aided_lock_seen_;
  aided_lock_seen_ = false;
  return locked;
}

void ReceiverChannel::add_to(NavigationStatus& status) const {
  status.prn = prn();
  status.tracked_s += tracking_->seconds_tracked();
  status.subframes_decoded += decoder_->subframes_decoded();
  status.parity_failures += decoder_->parity_failures();
  status.ephemeris = status.ephemeris || decoder_->ephemeris().has_value();
}

std::optional<double> ReceiverChannel::transmit_time_sow(std::int64_t sample) const {
  return deepnav::transmit_time_sow(*decoder_, *tracking_, sample);
}

ChannelObservation ReceiverChannel::observe(const GpsTime& t_rx, double transmit_sow, std::int64_t sample,
                                            double sample_rate_hz, bool after_gap) const {
  // The travel time, across a week rollover between transmission and reception.
  const double travel_s = seconds_of_week_difference(t_rx.sow, transmit_sow);
  ChannelObservation o;
  o.prn = prn();
  o.pseudorange_m = gps::kSpeedOfLight_mps * travel_s;
  // Doppler from the carrier phase over the last 100 ms (the loop's instantaneous
  // frequency carries its own noise); the loop frequency until that much exists.
  o.doppler_hz = tracking_->mean_doppler_hz(kDopplerWindow_s).value_or(last_doppler_hz_);
  if (const auto mid = tracking_->mean_doppler_mid_sample(kDopplerWindow_s))
    o.doppler_offset_s = (*mid - static_cast<double>(sample)) / sample_rate_hz;
  o.carrier_phase_cycles = tracking_->carrier_phase_cycles();
  o.cn0_dbhz = tracking_->cn0_dbhz();
  o.lock_time_s = tracking_->seconds_tracked();
  o.after_gap = after_gap;
  return o;
}

}  // namespace deepnav
