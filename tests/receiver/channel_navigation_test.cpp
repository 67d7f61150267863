// The channel and the navigation decoder together on a synthetic signal that carries a real
// LNAV stream (broadcast ephemeris of data/brdc0010.22n, encoded by signals/lnav_message):
// the decoded ephemeris, ionosphere and UTC parameters equal the source to the LSB, and the
// transmit time the pair computes for a sample is the signal's own.
#include <gtest/gtest.h>

#include <cmath>

#include "channel_test_signal.hpp"
#include "receiver/acquisition/guided_search.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "signals/lnav_message.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {

constexpr int kPrn = 10;
constexpr double kFs = 2.5e6;

struct Source {
  lnav::LnavContent content;
  std::int64_t first_bit = 0;  ///< week bit index of the signal's bit 0
  std::vector<std::uint8_t> bits;
};

/// Starts 3 s before subframe 1 of a frame whose subframe 4 is page 18 (ionosphere, UTC),
/// so one 30 s frame brings every parameter the test checks.
Source make_source() {
  const NavData nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  std::int64_t sf = 525600 / 6;
  while (!(lnav::subframe_id_at(sf) == 4 && lnav::page_at(sf) == 18)) ++sf;
  const std::int64_t frame_start = sf - 3;
  Source s;
  const Ephemeris* eph = nav.select(kPrn, GpsTime{2190, static_cast<double>(frame_start * 6)});
  if (!eph) throw std::runtime_error("no ephemeris for the test PRN in brdc0010.22n");
  s.content.eph = *eph;
  s.content.iono = nav.iono;
  s.content.utc = nav.utc;
  s.first_bit = frame_start * lnav::kBitsPerSubframe - 150;
  s.bits = lnav::lnav_bits(s.content, s.first_bit, 40 * 50);
  return s;
}

struct Decoded {
  NavDecoder nav{kPrn, 2190};
  double transmit_time_error_s = 1e9;
  double seconds = 0.0;
};

/// Tracks and decodes until ephemeris, ionosphere and UTC are all in, or 36 s.
Decoded run(const Source& src, double polarity) {
  testing::ChannelSignalSpec spec;
  spec.fs_hz = kFs;
  spec.prn = kPrn;
  spec.cn0_dbhz = 45.0;
  spec.seed = 77;
  spec.bit = [&](std::int64_t k) {
    const int level = src.bits.at(static_cast<std::size_t>(k)) ? -1 : 1;
    return static_cast<int>(polarity) * level;
  };
  testing::ChannelSignal sig(spec);
  TrackingConfig cfg;
  cfg.sample_rate_hz = kFs;
  TrackingChannel ch(cfg, ChannelStart{spec.prn, spec.doppler0_hz + 30.0, spec.code0_chips + 0.2, 0, 0, std::nullopt});
  const LoopBandwidths pull_in{15.0, 10.0, 1.0};
  const LoopBandwidths narrow{10.0, 0.0, 0.5};
  ScalarLoopController loop(spec.doppler0_hz + 30.0, 2, pull_in);
  Decoded d;
  for (int ms = 0; ms < 36000; ms += 100) {
    const SampleBlock b = sig.next(100);
    ch.process(b, [&](const CorrelatorEpoch& e) {
      loop.set_bandwidths(ch.state() == ChannelState::tracking ? narrow : pull_in);
      ch.apply(loop.update(e, ch.state() == ChannelState::pull_in));
    });
    for (const PromptBit& bit : ch.take_bits()) d.nav.add_bit(bit);
    d.seconds = (ms + 100) * 1e-3;
    if (d.nav.ephemeris() && d.nav.iono().valid && d.nav.utc().valid) break;
  }
  // Transmit time of the signal at the end of the last block against the signal's own.
  const std::int64_t sample = ch.next_sample();
  const double t = static_cast<double>(sample) / kFs;
  const double truth = src.first_bit * 0.02 + sig.code_chips(t) / gps::kCodeRate_cps;
  if (const auto tx = transmit_time_sow(d.nav, ch, sample)) d.transmit_time_error_s = *tx - truth;
  return d;
}

void expect_same_navigation_data(const Decoded& d, const lnav::LnavContent& c) {
  ASSERT_TRUE(d.nav.ephemeris().has_value()) << "after " << d.seconds << " s";
  const Ephemeris& e = *d.nav.ephemeris();
  const Ephemeris& s = c.eph;
  EXPECT_EQ(e.prn, kPrn);
  EXPECT_EQ(e.week, s.week);
  EXPECT_EQ(e.iode, s.iode);
  EXPECT_EQ(e.iodc, s.iodc);
  EXPECT_EQ(e.health, s.health);
  // Within one LSB of each field (IS-GPS-200 tables 20-I and 20-III).
  EXPECT_NEAR(e.toe_s, s.toe_s, 16.0);
  EXPECT_NEAR(e.toc_s, s.toc_s, 16.0);
  EXPECT_NEAR(e.sqrt_a, s.sqrt_a, std::ldexp(1.0, -19));
  EXPECT_NEAR(e.e, s.e, std::ldexp(1.0, -33));
  EXPECT_NEAR(e.m0_rad, s.m0_rad, std::ldexp(M_PI, -31));
  EXPECT_NEAR(e.omega0_rad, s.omega0_rad, std::ldexp(M_PI, -31));
  EXPECT_NEAR(e.i0_rad, s.i0_rad, std::ldexp(M_PI, -31));
  EXPECT_NEAR(e.omega_rad, s.omega_rad, std::ldexp(M_PI, -31));
  EXPECT_NEAR(e.delta_n_radps, s.delta_n_radps, std::ldexp(M_PI, -43));
  EXPECT_NEAR(e.omega_dot_radps, s.omega_dot_radps, std::ldexp(M_PI, -43));
  EXPECT_NEAR(e.idot_radps, s.idot_radps, std::ldexp(M_PI, -43));
  EXPECT_NEAR(e.crs_m, s.crs_m, std::ldexp(1.0, -5));
  EXPECT_NEAR(e.crc_m, s.crc_m, std::ldexp(1.0, -5));
  EXPECT_NEAR(e.cuc_rad, s.cuc_rad, std::ldexp(1.0, -29));
  EXPECT_NEAR(e.cus_rad, s.cus_rad, std::ldexp(1.0, -29));
  EXPECT_NEAR(e.cic_rad, s.cic_rad, std::ldexp(1.0, -29));
  EXPECT_NEAR(e.cis_rad, s.cis_rad, std::ldexp(1.0, -29));
  EXPECT_NEAR(e.af0_s, s.af0_s, std::ldexp(1.0, -31));
  EXPECT_NEAR(e.af1_sps, s.af1_sps, std::ldexp(1.0, -43));
  EXPECT_NEAR(e.af2_sps2, s.af2_sps2, std::ldexp(1.0, -55));
  EXPECT_NEAR(e.tgd_s, s.tgd_s, std::ldexp(1.0, -31));

  ASSERT_TRUE(d.nav.iono().valid);
  const double alpha_lsb[4] = {std::ldexp(1.0, -30), std::ldexp(1.0, -27), std::ldexp(1.0, -24), std::ldexp(1.0, -24)};
  const double beta_lsb[4] = {std::ldexp(1.0, 11), std::ldexp(1.0, 14), std::ldexp(1.0, 16), std::ldexp(1.0, 16)};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(d.nav.iono().alpha[k], c.iono.alpha[k], alpha_lsb[k]) << k;
    EXPECT_NEAR(d.nav.iono().beta[k], c.iono.beta[k], beta_lsb[k]) << k;
  }
  ASSERT_TRUE(d.nav.utc().valid);
  EXPECT_NEAR(d.nav.utc().a0_s, c.utc.a0_s, std::ldexp(1.0, -30));
  EXPECT_NEAR(d.nav.utc().a1_sps, c.utc.a1_sps, std::ldexp(1.0, -50));
  EXPECT_EQ(d.nav.utc().delta_t_ls, c.utc.delta_t_ls);
}

TEST(ChannelNavigation, DecodesARealLnavStreamAndTransmitTimeInBothPolarities) {
  const Source src = make_source();
  const Decoded upright = run(src, 1.0);
  expect_same_navigation_data(upright, src.content);
  EXPECT_EQ(upright.nav.parity_failures(), 0);
  EXPECT_LT(upright.seconds, 30.0);
  // Within 0.03 chip: the code tracking error, not a bit or a millisecond.
  EXPECT_LT(std::abs(upright.transmit_time_error_s), 0.03 / gps::kCodeRate_cps);

  // The same signal with every data bit inverted: the loops (Costas, FLL, envelope DLL)
  // run identically, and the preamble finds the opposite polarity.
  const Decoded inverted = run(src, -1.0);
  expect_same_navigation_data(inverted, src.content);
  EXPECT_EQ(inverted.nav.polarity(), -upright.nav.polarity());
  EXPECT_NE(upright.nav.polarity(), 0);
  EXPECT_LT(std::abs(inverted.transmit_time_error_s), 0.03 / gps::kCodeRate_cps);
}

TEST(ChannelNavigation, AGuidedStartHasTheSignalsTimeAndBitsBeforeAnySubframe) {
  // A filter predicts the signal 0.4 chip and 8 Hz off; the guided search finds it and the
  // channel starts there with its bit edge and the decoder's time taken from the
  // prediction. The transmit time is right from the first second (no subframe decoded yet),
  // and every subframe decoded afterwards agrees with it.
  const Source src = make_source();
  testing::ChannelSignalSpec spec;
  spec.fs_hz = kFs;
  spec.prn = kPrn;
  spec.cn0_dbhz = 45.0;
  spec.seed = 78;
  spec.bit = [&](std::int64_t k) { return src.bits.at(static_cast<std::size_t>(k)) ? -1 : 1; };
  testing::ChannelSignal sig(spec);
  const auto truth_sow = [&](std::int64_t sample) {
    return src.first_bit * 0.02 + sig.code_chips(static_cast<double>(sample) / kFs) / gps::kCodeRate_cps;
  };
  SignalPrediction p;
  p.prn = kPrn;
  p.transmit_sow = truth_sow(0) - 0.4 / gps::kCodeRate_cps;
  p.doppler_hz = spec.doppler0_hz - 8.0;
  p.doppler_rate_hzps = spec.doppler_rate_hzps;
  p.code_sigma_chips = 0.05;
  p.doppler_sigma_hz = 1.0;
  GuidedSearch search({}, p, kFs, 0.0);
  std::int64_t end = 0;
  while (search.outcome() == GuidedSearch::Outcome::searching) {
    const SampleBlock b = sig.next(100);
    search.add(b);
    end = b.first_sample_index + static_cast<std::int64_t>(b.samples.size());
  }
  ASSERT_EQ(search.outcome(), GuidedSearch::Outcome::found);
  const GuidedStart start = search.start_at(end, 0);
  TrackingConfig cfg;
  cfg.sample_rate_hz = kFs;
  TrackingChannel ch(cfg, start.channel);
  EXPECT_EQ(ch.state(), ChannelState::tracking);
  NavDecoder nav(kPrn, 2190);
  nav.seed_time(0, start.period0_transmit_sow);
  EXPECT_TRUE(nav.synchronised());
  EXPECT_TRUE(nav.seeded());
  ScalarLoopController loop(start.channel.doppler_hz, 2, LoopBandwidths{10.0, 0.0, 0.5});
  int bits = 0;
  for (int ms = 0; ms < 36000; ms += 100) {
    const SampleBlock b = sig.next(100);
    ch.process(b, [&](const CorrelatorEpoch& e) {
      EXPECT_TRUE(e.bit_synced);
      ch.apply(loop.update(e, false));
    });
    for (const PromptBit& bit : ch.take_bits()) {
      // Every bit the channel assembles starts on one of the signal's bit edges.
      EXPECT_NEAR(std::remainder(truth_sow(bit.first_sample), 0.02), 0.0, 2e-6);
      nav.add_bit(bit);
      ++bits;
    }
    if (ms == 1000) {
      ASSERT_EQ(nav.subframes_decoded(), 0);
      const auto tx = transmit_time_sow(nav, ch, ch.next_sample());
      ASSERT_TRUE(tx.has_value());
      EXPECT_LT(std::abs(*tx - truth_sow(ch.next_sample())), 0.05 / gps::kCodeRate_cps);
    }
  }
  EXPECT_GT(bits, 1700);
  EXPECT_GE(nav.subframes_decoded(), 5);
  EXPECT_EQ(nav.inconsistent_subframes(), 0);
  EXPECT_FALSE(nav.seeded());
  ASSERT_TRUE(nav.ephemeris().has_value());
  EXPECT_EQ(nav.ephemeris()->iode, src.content.eph.iode);
  const auto tx = transmit_time_sow(nav, ch, ch.next_sample());
  ASSERT_TRUE(tx.has_value());
  EXPECT_LT(std::abs(*tx - truth_sow(ch.next_sample())), 0.05 / gps::kCodeRate_cps);
}

}  // namespace
}  // namespace deepnav
