#include "receiver/tracking/channel_controller.hpp"

namespace deepnav {

ScalarChannelControl::ScalarChannelControl(double initial_doppler_hz, int pll_order, const LoopBandwidths& pull_in,
                                           const LoopBandwidths& tracking)
    : loop_(initial_doppler_hz, pll_order, pull_in), pull_in_(pull_in), tracking_(tracking) {}

void ScalarChannelControl::select_bandwidths(const ChannelView& view) {
  loop_.set_bandwidths(view.channel.state() == ChannelState::tracking ? tracking_ : pull_in_);
}

ChannelDecision ScalarChannelControl::on_epoch(const CorrelatorEpoch& epoch, const ChannelView& view) {
  const bool pulling_in = view.channel.state() == ChannelState::pull_in;
  select_bandwidths(view);
  ChannelDecision d;
  d.owns_epoch = true;
  d.command = loop_.update(epoch, pulling_in);
  return d;
}

void ScalarChannelControl::follow(const CorrelatorEpoch& epoch, const ChannelView& view) {
  select_bandwidths(view);
  loop_.reset(epoch.carrier_doppler_hz);
}

}  // namespace deepnav
