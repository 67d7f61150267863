// The steered side of a channel between the filter and the tracking loop: the filter's NCO
// commands published into the controller reach the channel between blocks (once each), the
// integrations come back as discriminator samples that measure the signal whatever the
// replica was commanded to, a released channel returns to its own loops, and weak channels
// integrate across data bits with the data wiped off exactly where the bits are predicted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <vector>

#include "aiding/steered_channel_controller.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "steered_channel_rig.hpp"

namespace deepnav::aiding {
namespace {

using testing::kRigSampleRate_hz;
using testing::RigSignal;
using testing::SteeredChannelRig;

constexpr int kPrn = 10;
constexpr double kStartSow = 525600.0 - 3.0;  ///< 3 s before a subframe 1 (sow a multiple of 30 s)

/// A strong signal with random data bits.
RigSignal strong_signal() {
  RigSignal s;
  s.transmit_sow = kStartSow + 0.0123456;
  s.doppler_hz = 1250.0;
  s.doppler_rate_hzps = 0.5;
  s.cn0_dbhz = 45.0;
  s.seed = 11;
  return s;
}

/// Signal minus replica transmit time of a sample against the truth (chips).
double measured_transmit_error_chips(const DiscriminatorSample& d, const SteeredChannelRig& rig) {
  const double measured = d.replica_transmit_sow + d.code_error_chips / gps::kCodeRate_cps;
  return (measured - rig.truth_transmit_sow(d.mid_sample)) * gps::kCodeRate_cps;
}

TEST(SteeredChannelController, CommandsGoOutOnceAndSamplesMeasureTheSignalWhereverTheReplicaIs) {
  const lnav::LnavContent content = testing::broadcast_content(kPrn, kStartSow);
  SteeredChannelRig rig(strong_signal(), content.eph, nullptr);
  const UltraTightConfig cfg;
  const Engagement engagement = Engagement::all;
  SteeredChannelController controller(cfg, kRigSampleRate_hz, engagement);

  bool every_epoch_owned = true;
  rig.track(20, controller,
            [&](const CorrelatorEpoch&, const ChannelDecision& d) { every_epoch_owned &= d.owns_epoch; });
  EXPECT_TRUE(every_epoch_owned);
  EXPECT_EQ(controller.take_samples().size(), 2u);
  EXPECT_TRUE(controller.steered());
  EXPECT_FALSE(rig.loss_detection());  // the filter keeps the channel through fades

  std::int64_t last_mid = -1;
  int samples = 0, doppler_samples = 0, commands_with_phase_correction = 0;
  double worst_transmit_error_chips = 0.0, worst_doppler_error_hz = 0.0;
  std::complex<double> last_prompt;
  for (int block = 0; block < 100; ++block) {  // 2 s of 20 ms blocks
    const std::int64_t block_start = rig.end_sample();
    rig.track(20, controller, [&](const CorrelatorEpoch& e, const ChannelDecision&) { last_prompt = e.prompt; });
    const std::vector<DiscriminatorSample> taken = controller.take_samples();
    // One sample per 10 ms integration, in time order, inside the block.
    EXPECT_EQ(taken.size(), 2u);
    for (const DiscriminatorSample& d : taken) {
      EXPECT_EQ(d.prn, kPrn);
      EXPECT_GT(d.mid_sample, last_mid);
      EXPECT_GT(d.mid_sample, block_start);
      EXPECT_LT(d.mid_sample, rig.end_sample());
      EXPECT_EQ(std::get<Ephemeris>(d.ephemeris).prn, kPrn);
      last_mid = d.mid_sample;
      ++samples;
      if (block >= 25) {  // once the loops have settled
        worst_transmit_error_chips =
            std::max(worst_transmit_error_chips, std::abs(measured_transmit_error_chips(d, rig)));
        EXPECT_TRUE(d.measurement);
        if (d.doppler_hz) {
          ++doppler_samples;
          worst_doppler_error_hz =
              std::max(worst_doppler_error_hz, std::abs(*d.doppler_hz - rig.truth_doppler_hz(d.doppler_sample)));
        }
      }
    }
    EXPECT_TRUE(controller.take_samples().empty());  // taken once
    controller.publish(rig.exact_command());
    const ChannelDecision out = rig.between_blocks(controller);
    ASSERT_TRUE(out.command.has_value());
    EXPECT_DOUBLE_EQ(out.command->carrier_doppler_hz, rig.exact_command().carrier_doppler_hz);
    if (out.command->carrier_phase_correction_cycles) ++commands_with_phase_correction;
    EXPECT_FALSE(rig.between_blocks(controller).command.has_value());  // collected once
  }
  EXPECT_EQ(samples, 200);
  EXPECT_LT(worst_transmit_error_chips, 0.1);  // 5 sigma of 10 ms at 45 dB-Hz
  EXPECT_GT(doppler_samples, 10);
  EXPECT_LT(worst_doppler_error_hz, 0.5);
  // The Costas corrections ride on the commands and have pulled the carrier phase in
  // (the signal started 0.3 cycles from the replica).
  EXPECT_GT(commands_with_phase_correction, 50);
  EXPECT_LT(std::abs(costas_phase_error_cycles(last_prompt)), 0.05);

  // A code phase correction moves the replica: the discriminator sees it, the measured
  // transmit time does not.
  NcoCommand step = rig.exact_command();
  step.code_phase_correction_chips = 0.2;
  controller.publish(step);
  rig.between_blocks(controller);
  const std::int64_t step_sample = rig.end_sample();
  rig.track(40, controller);
  int after_step = 0;
  for (const DiscriminatorSample& d : controller.take_samples()) {
    const auto half = static_cast<std::int64_t>(d.integration_s * kRigSampleRate_hz / 2);
    if (d.mid_sample - half < step_sample) continue;  // begun before the step
    ++after_step;
    EXPECT_NEAR(d.code_error_chips, -0.2, 0.06);  // the replica leads the signal
    EXPECT_NEAR(measured_transmit_error_chips(d, rig), 0.0, 0.1);
  }
  EXPECT_GE(after_step, 2);
}

TEST(SteeredChannelController, ReleasedChannelsReturnToTheirOwnLoops) {
  const lnav::LnavContent content = testing::broadcast_content(kPrn, kStartSow);
  SteeredChannelRig rig(strong_signal(), content.eph, nullptr);
  const UltraTightConfig cfg;
  Engagement engagement = Engagement::all;
  SteeredChannelController controller(cfg, kRigSampleRate_hz, engagement);
  rig.track(100, controller);
  ASSERT_TRUE(controller.steered());

  // The filter gives the channel back: its loss detection is on again, no command follows.
  controller.publish(rig.exact_command());
  controller.publish_release();
  EXPECT_FALSE(controller.steered());
  const ChannelDecision released = rig.between_blocks(controller);
  EXPECT_EQ(released.loss_detection, std::optional<bool>(true));
  EXPECT_TRUE(rig.loss_detection());

  // Still engaged, the next integration takes it over again.
  rig.track(20, controller);
  EXPECT_TRUE(controller.steered());
  EXPECT_FALSE(rig.loss_detection());

  // release() also drops what was queued.
  rig.track(20, controller);
  controller.release();
  EXPECT_TRUE(controller.take_samples().empty());
  EXPECT_EQ(rig.between_blocks(controller).loss_detection, std::optional<bool>(true));

  // Not engaged: the controller leaves every integration to the channel's loops.
  engagement = Engagement::none;
  bool any_owned = false;
  rig.track(100, controller, [&](const CorrelatorEpoch&, const ChannelDecision& d) { any_owned |= d.owns_epoch; });
  EXPECT_FALSE(any_owned);
  EXPECT_FALSE(controller.steered());
  EXPECT_TRUE(controller.take_samples().empty());
}

/// The subframe of the week the transmit time falls in.
std::int64_t subframe_of(double transmit_sow) { return static_cast<std::int64_t>(std::floor(transmit_sow / 6.0)); }

TEST(SteeredChannelController, WipesTheDataOffWhereTheBitsArePredicted) {
  // A weak signal with the real LNAV stream, its subframes 1-3 assisted from the same
  // ephemeris: once the decoder knows the bits' polarity (its first subframe), the long
  // integrations run coherently across the bits of subframes 2 and 3 and of subframe 4's
  // header, and fall back to bits summed in power in subframe 4's data words, which
  // nothing predicts.
  const lnav::LnavContent content = testing::broadcast_content(kPrn, kStartSow);
  RigSignal weak = strong_signal();
  weak.cn0_dbhz = 26.0;
  weak.seed = 12;
  SteeredChannelRig rig(weak, content.eph, &content);
  UltraTightConfig cfg;
  cfg.long_integration.assist_data_bits = true;
  const Engagement engagement = Engagement::all;
  SteeredChannelController controller(cfg, kRigSampleRate_hz, engagement);

  // Each subframe begins with its TLM and HOW words (60 bits, 1.2 s), which the predictor
  // knows once it has learned a subframe; only subframe 4's data words are unknown.
  constexpr double kHeader_s = 1.2;
  struct Integration {
    std::int64_t subframe;  ///< of its start and end (-1: it spans two)
    double start_s, end_s;  ///< into that subframe
    bool wiped;
    double piece_s;
    bool polarity_known;
  };
  std::vector<Integration> long_ones;
  const double first_subframe_1 = kStartSow + 3.0;
  while (rig.truth_transmit_sow(rig.end_sample()) < first_subframe_1 + 4.0 * 6.0) {  // to the end of subframe 4
    rig.track(20, controller);
    for (const DiscriminatorSample& d : controller.take_samples()) {
      if (d.integration_s < 0.015) continue;  // the channel's own 10 ms integrations
      const auto span = static_cast<std::int64_t>(std::llround(d.integration_s * kRigSampleRate_hz));
      const double start = rig.truth_transmit_sow(d.mid_sample - span), end = rig.truth_transmit_sow(d.mid_sample);
      const std::int64_t sf = subframe_of(start);
      long_ones.push_back({sf == subframe_of(end) ? sf : -1, start - 6.0 * static_cast<double>(sf),
                           end - 6.0 * static_cast<double>(sf), d.data_wiped, d.piece_s,
                           rig.decoder().polarity() != 0});
    }
    controller.publish(rig.exact_command());
    rig.between_blocks(controller);
  }
  ASSERT_TRUE(controller.long_integration());
  ASSERT_NE(rig.decoder().polarity(), 0);
  const std::int64_t sf1 = subframe_of(first_subframe_1);
  int unknown_polarity = 0, wiped_before_polarity = 0, in_2_3 = 0, wiped_2_3 = 0, header_4 = 0, wiped_header_4 = 0,
      data_4 = 0, wiped_data_4 = 0;
  for (const Integration& i : long_ones) {
    if (!i.polarity_known) {
      ++unknown_polarity;
      wiped_before_polarity += i.wiped;
    } else if (i.subframe == sf1 + 1 || i.subframe == sf1 + 2) {
      ++in_2_3;
      wiped_2_3 += i.wiped;
    } else if (i.subframe == sf1 + 3 && i.end_s <= kHeader_s + 1e-6) {
      ++header_4;
      wiped_header_4 += i.wiped;
    } else if (i.subframe == sf1 + 3 && i.start_s >= kHeader_s - 1e-6) {
      ++data_4;
      wiped_data_4 += i.wiped;
      EXPECT_NEAR(i.piece_s, 0.02, 1e-9);  // 20 ms bits summed in power
    }
  }
  EXPECT_GT(unknown_polarity, 0);
  EXPECT_EQ(wiped_before_polarity, 0);
  ASSERT_GT(in_2_3, 40);
  EXPECT_GT(wiped_2_3, 0.9 * in_2_3);
  ASSERT_GT(header_4, 2);
  EXPECT_GT(wiped_header_4, 0.8 * header_4);
  ASSERT_GE(data_4, 3);
  EXPECT_EQ(wiped_data_4, 0);
  EXPECT_EQ(controller.wipeoff().monitor().alarms(), 0);
}

}  // namespace
}  // namespace deepnav::aiding
