#pragma once
// One channel of a synthetic C/A signal whose transmit time is known at every sample, a
// TrackingChannel started on it with its bit edge and a NavDecoder seeded with its time (a
// guided start), driven through a ChannelController the way the receiver drives one:
// every integration to on_epoch() (its decisions carried out), the data bits to the
// decoder, and between blocks whatever the controller published.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "../receiver/channel_test_signal.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "signals/lnav_message.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding::testing {

inline constexpr double kRigSampleRate_hz = 2.5e6;
inline constexpr int kRigWeek = 2190;  ///< of data/brdc0010.22n

inline NavData broadcast_navigation_data() {
  return read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
}

/// A satellite's broadcast ephemeris, ionosphere and UTC of data/brdc0010.22n near `sow`.
inline lnav::LnavContent broadcast_content(int prn, double sow) {
  const NavData nav = broadcast_navigation_data();
  const Ephemeris* eph = nav.select(prn, GpsTime{kRigWeek, sow});
  if (!eph) throw std::runtime_error("no ephemeris of PRN " + std::to_string(prn) + " in brdc0010.22n");
  lnav::LnavContent content;
  content.eph = *eph;
  content.iono = nav.iono;
  content.utc = nav.utc;
  return content;
}

struct RigSignal {
  double transmit_sow = 0.0;  ///< transmit time of the signal arriving at sample 0
  double doppler_hz = 1000.0;
  double doppler_rate_hzps = 0.5;
  double cn0_dbhz = 45.0;
  std::uint64_t seed = 5;
};

class SteeredChannelRig {
 public:
  /// The signal of `ephemeris`'s satellite; it carries the LNAV data of `data_bits` (its
  /// week bit index from the transmit time), or seeded random bits when that is null.
  SteeredChannelRig(const RigSignal& s, const Ephemeris& ephemeris, const lnav::LnavContent* data_bits)
      : first_bit_(static_cast<std::int64_t>(std::floor(s.transmit_sow / 0.02))),
        signal_(spec(s, ephemeris.prn, first_bit_, data_bits, bits_)),
        channel_(tracking_config(), channel_start(signal_)),
        decoder_(ephemeris.prn, kRigWeek),
        ephemeris_(ephemeris) {
    // The channel's code period 0 is the signal's period floor(code0 / 1023).
    const auto period0 = static_cast<std::int64_t>(std::floor(signal_.spec().code0_chips / 1023.0));
    decoder_.seed_time(0, static_cast<double>(first_bit_) * 0.02 + static_cast<double>(period0) * 1e-3);
  }
  // The signal reads the data bits the rig holds.
  SteeredChannelRig(const SteeredChannelRig&) = delete;
  SteeredChannelRig& operator=(const SteeredChannelRig&) = delete;

  /// The signal's transmit time (seconds of week) at a sample.
  double truth_transmit_sow(std::int64_t sample) const {
    return static_cast<double>(first_bit_) * 0.02 +
           signal_.code_chips(static_cast<double>(sample) / kRigSampleRate_hz) / gps::kCodeRate_cps;
  }
  double truth_doppler_hz(std::int64_t sample) const {
    return signal_.doppler_hz(static_cast<double>(sample) / kRigSampleRate_hz);
  }

  /// `ms` of signal through the channel, each integration to `controller` (what it decides
  /// carried out, as the receiver does) and to `on_epoch` when given; the bits to the decoder.
  template <typename OnEpoch>
  void track(int ms, ChannelController& controller, OnEpoch on_epoch) {
    const SampleBlock b = signal_.next(ms);
    channel_.process(b, [&](const CorrelatorEpoch& e) {
      const ChannelDecision d = controller.on_epoch(e, view());
      carry_out(d);
      on_epoch(e, d);
    });
    for (const PromptBit& bit : channel_.take_bits()) decoder_.add_bit(bit);
    end_sample_ = b.first_sample_index + static_cast<std::int64_t>(b.samples.size());
  }
  void track(int ms, ChannelController& controller) {
    track(ms, controller, [](const CorrelatorEpoch&, const ChannelDecision&) {});
  }

  /// Between blocks: what the controller published, carried out; returned for inspection.
  ChannelDecision between_blocks(ChannelController& controller) {
    const ChannelDecision d = controller.between_blocks(view());
    carry_out(d);
    return d;
  }

  /// The NCO command of a filter that knows the signal: its Doppler at the block's end.
  NcoCommand exact_command() const {
    NcoCommand c;
    c.carrier_doppler_hz = truth_doppler_hz(end_sample_);
    c.code_rate_cps = gps::kCodeRate_cps * (1.0 + c.carrier_doppler_hz / gps::kL1_Hz);
    return c;
  }

  ChannelView view() const { return {channel_, decoder_, &ephemeris_, true}; }
  const TrackingChannel& channel() const { return channel_; }
  const NavDecoder& decoder() const { return decoder_; }
  const Ephemeris& ephemeris() const { return ephemeris_; }
  std::int64_t end_sample() const { return end_sample_; }
  bool loss_detection() const { return loss_detection_; }

 private:
  static TrackingConfig tracking_config() {
    TrackingConfig c;
    c.sample_rate_hz = kRigSampleRate_hz;
    return c;
  }

  static ::deepnav::testing::ChannelSignalSpec spec(const RigSignal& s, int prn, std::int64_t first_bit,
                                                    const lnav::LnavContent* content, std::vector<std::uint8_t>& bits) {
    ::deepnav::testing::ChannelSignalSpec sp;
    sp.fs_hz = kRigSampleRate_hz;
    sp.prn = prn;
    sp.cn0_dbhz = s.cn0_dbhz;
    sp.doppler0_hz = s.doppler_hz;
    sp.doppler_rate_hzps = s.doppler_rate_hzps;
    sp.code0_chips = (s.transmit_sow - static_cast<double>(first_bit) * 0.02) * gps::kCodeRate_cps;
    sp.seed = s.seed;
    if (content) {
      bits = lnav::lnav_bits(*content, first_bit, 60 * 50);  // a minute of data
      sp.bit = [&bits](std::int64_t k) { return bits.at(static_cast<std::size_t>(k)) ? -1 : 1; };
    }
    return sp;
  }

  /// Started where the signal is, its bit edge known (a guided start).
  static ChannelStart channel_start(const ::deepnav::testing::ChannelSignal& signal) {
    const double code0 = signal.spec().code0_chips;
    const auto period0 = static_cast<std::int64_t>(std::floor(code0 / 1023.0));
    ChannelStart st;
    st.prn = signal.spec().prn;
    st.doppler_hz = signal.spec().doppler0_hz;
    st.code_phase_chips = code0 - static_cast<double>(period0) * 1023.0;
    st.sample_index = 0;
    st.bit_edge_period = (20 - period0 % 20) % 20;  // the signal's bits start every 20th period
    return st;
  }

  void carry_out(const ChannelDecision& d) {
    if (d.command) channel_.apply(*d.command);
    if (d.loss_detection) {
      channel_.set_loss_detection(*d.loss_detection);
      loss_detection_ = *d.loss_detection;
    }
  }

  std::int64_t first_bit_;
  std::vector<std::uint8_t> bits_;
  ::deepnav::testing::ChannelSignal signal_;
  TrackingChannel channel_;
  NavDecoder decoder_;
  Ephemeris ephemeris_;
  std::int64_t end_sample_ = 0;
  bool loss_detection_ = true;
};

}  // namespace deepnav::aiding::testing
