#include "receiver/galileo_channel.hpp"

#include <cmath>

#include "signals/galileo/galileo_constants.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {

GalileoChannel::GalileoChannel(const E1TrackingConfig& tracking, const E1LoopSettings& loops,
                               const E1ChannelStart& start, E1ChannelController* steered)
    : tracking_(tracking, start), loops_(start.doppler_hz, loops), steered_(steered), decoder_(start.satellite.prn) {}

void GalileoChannel::end() {
  if (steered_) steered_->channel_ended();
  steered_now_ = false;
  aided_lock_.reset();
}

E1ChannelView GalileoChannel::view(const galileo::GalileoEphemeris* ephemeris, bool clock_set) const {
  return E1ChannelView{tracking_, decoder_, ephemeris, clock_set};
}

void GalileoChannel::carry_out(const E1ChannelDecision& d) {
  if (d.loss_detection) {
    tracking_.set_loss_detection(*d.loss_detection);
    if (*d.loss_detection) {  // given back: the channel's own criterion again
      steered_now_ = false;
      aided_lock_.reset();
    }
  }
  if (d.coherent_periods) tracking_.set_coherent_periods(*d.coherent_periods);
  if (d.command) tracking_.apply(*d.command);
}

void GalileoChannel::collect_published(const galileo::GalileoEphemeris* ephemeris, bool clock_set) {
  if (steered_) carry_out(steered_->between_blocks(view(ephemeris, clock_set)));
}

double GalileoChannel::cn0_dbhz() const { return aided_lock_ ? aided_lock_->cn0_dbhz : tracking_.cn0_dbhz(); }

void GalileoChannel::track(const SampleBlock& block, const galileo::GalileoEphemeris* ephemeris, bool clock_set) {
  tracking_.process(block, [&](const E1CorrelatorEpoch& e) {
    E1ChannelDecision outside;
    if (steered_) {
      outside = steered_->on_epoch(e, view(ephemeris, clock_set));
      carry_out(outside);
    }
    steered_now_ = outside.owns_epoch;
    if (outside.owns_epoch) {
      // Ready to take the channel back where the filter leaves it.
      loops_.follow(e);
      aided_lock_ = outside.lock;
    } else {
      aided_lock_.reset();
      // Each integration's command acts from the very next sample.
      tracking_.apply(loops_.update(e));
    }
    decoder_.add(e.symbols);
    tracked_s_ += e.integration_s;
    recent_.push_back({e.first_sample, e.first_sample + e.samples, e.integration_s, e.carrier_doppler_hz});
    double kept_s = 0.0;
    for (const DopplerSpan& d : recent_) kept_s += d.seconds;
    while (recent_.size() > 1 && kept_s - recent_.front().seconds >= kDopplerWindow_s) {
      kept_s -= recent_.front().seconds;
      recent_.pop_front();
    }
  });
}

bool GalileoChannel::observable(double lost_cn0_dbhz) const {
  if (tracking_.state() != E1ChannelState::tracking || !decoder_.navigation().time_mark()) return false;
  if (steered_now_) return aided_lock_ && aided_lock_->locked;
  return tracking_.cn0_dbhz() >= lost_cn0_dbhz;
}

std::optional<double> GalileoChannel::transmit_time_sow(std::int64_t sample) const {
  return e1_transmit_time_sow(decoder_, tracking_.code_chips_at(sample));
}

double GalileoChannel::mean_doppler_hz() const {
  double seconds = 0.0, cycles = 0.0;
  for (const DopplerSpan& d : recent_) {
    seconds += d.seconds;
    cycles += d.seconds * d.doppler_hz;
  }
  return seconds > 0.0 ? cycles / seconds : loops_.doppler_hz();
}

ChannelObservation GalileoChannel::observe(const GpsTime& t_rx, double transmit_sow, std::int64_t sample,
                                           double sample_rate_hz, bool after_gap) const {
  // The travel time, across a week rollover between transmission and reception.
  const double travel_s = seconds_of_week_difference(t_rx.sow, transmit_sow);
  ChannelObservation o;
  o.system = GnssSystem::galileo;
  o.prn = svid();
  o.pseudorange_m = gps::kSpeedOfLight_mps * travel_s;
  o.doppler_hz = mean_doppler_hz();
  // The mean refers to the middle of the integrations it averages.
  if (!recent_.empty()) {
    const double mid = 0.5 * static_cast<double>(recent_.front().first_sample + recent_.back().end_sample);
    o.doppler_offset_s = (mid - static_cast<double>(sample)) / sample_rate_hz;
  }
  o.carrier_phase_cycles = tracking_.carrier_phase_cycles();
  o.cn0_dbhz = cn0_dbhz();
  o.lock_time_s = tracked_s_;
  o.after_gap = after_gap;
  o.aided_lock = aided_lock_.has_value();
  return o;
}

}  // namespace deepnav
