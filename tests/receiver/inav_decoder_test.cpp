// I/NAV decoding in the receiver: page sync in either polarity, FEC, page pairing, CRC,
// the ephemeris/GGTO/UTC/time assembly, and corrupted pages never used; on symbol streams
// made with the signal layer's encoders, and on the symbols a tracked E1 channel produces.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "e1_test_signal.hpp"
#include "inav_test_message.hpp"
#include "receiver/navdata/inav_navigation.hpp"
#include "receiver/tracking/e1_tracking_channel.hpp"
#include "receiver/tracking/e1_tracking_loops.hpp"

namespace deepnav {
namespace {

using testing::inav_test_symbols;
using testing::kInavTestTow0;
constexpr std::int64_t kSamplesPerSymbol = 16000;  // 4 ms at 4 Msps

/// Soft symbols of `levels` times `polarity`, amplitude 1 with Gaussian noise of `sigma`,
/// after `lead` random symbols, numbered from code period 0.
std::vector<E1bSymbol> noisy_symbols(const std::vector<int>& levels, double polarity, double sigma, int lead,
                                     std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<E1bSymbol> out;
  const auto push = [&](double level) {
    const auto k = static_cast<std::int64_t>(out.size());
    out.push_back(E1bSymbol{polarity * level + noise(rng), k * kSamplesPerSymbol, k, false});
  };
  for (int k = 0; k < lead; ++k) push((rng() & 1) ? 1.0 : -1.0);
  for (int level : levels) push(level);
  return out;
}

TEST(InavDecoder, RecoversTheMessageFromNoisySymbolsInEitherPolarity) {
  const std::vector<int> levels = inav_test_symbols({0, 1, 2, 3, 4, 5, 6, 10});
  const int lead = 137;
  for (double polarity : {1.0, -1.0}) {
    InavDecoder decoder;
    decoder.add(noisy_symbols(levels, polarity, 0.45, lead, 3));
    EXPECT_EQ(decoder.sync().polarity(), polarity > 0 ? 1 : -1);
    EXPECT_EQ(decoder.pages().counts().pages, 8);
    EXPECT_EQ(decoder.pages().counts().crc_failures, 0);
    const InavNavigation& nav = decoder.navigation();
    ASSERT_TRUE(nav.ephemeris().has_value());
    testing::expect_same_galileo_ephemeris(*nav.ephemeris(), testing::inav_test_expected_ephemeris());
    // The words' rounding aside, the ephemeris is the one sent.
    EXPECT_NEAR(nav.ephemeris()->orbit.sqrt_a, testing::inav_test_ephemeris().orbit.sqrt_a, 1e-5);
    EXPECT_EQ(nav.ephemeris()->week, 1173);
    ASSERT_TRUE(nav.ggto().has_value());
    EXPECT_NEAR(nav.ggto()->a0g_s, testing::inav_test_ggto().a0g_s, 0x1p-35);
    EXPECT_EQ(nav.ggto()->t0g_s, 86400);
    ASSERT_TRUE(nav.utc().has_value());
    EXPECT_EQ(nav.utc()->delta_t_ls, 18);
    // Time: the last mark is word 6's (page 6), and every page start reads its own TOW.
    ASSERT_TRUE(nav.time_mark().has_value());
    EXPECT_EQ(nav.time_mark()->tow_s, kInavTestTow0 + 12);
    EXPECT_EQ(nav.time_mark()->code_period, lead + 6 * 500);
    EXPECT_EQ(nav.time_mark()->first_sample, (lead + 6 * 500) * kSamplesPerSymbol);
    EXPECT_EQ(nav.time_mark()->week, 1173);
    for (int page = 0; page < 8; ++page)
      EXPECT_DOUBLE_EQ(*nav.tow_at_code_period(lead + 500 * page), kInavTestTow0 + 2.0 * page);
  }
}

TEST(InavDecoder, FollowsAPolarityFlipBetweenPages) {
  // The channel's symbols change sign when its pilot fixes the carrier phase.
  std::vector<int> levels = inav_test_symbols({1, 2, 3, 4, 5});
  for (std::size_t k = 1500; k < levels.size(); ++k) levels[k] = -levels[k];
  InavDecoder decoder;
  decoder.add(noisy_symbols(levels, 1.0, 0.3, 20, 4));
  EXPECT_EQ(decoder.sync().polarity(), -1);
  EXPECT_EQ(decoder.pages().counts().pages, 5);
  EXPECT_TRUE(decoder.navigation().ephemeris().has_value());
}

TEST(InavDecoder, CorruptedPagesAreCountedAndNeverUsed) {
  std::vector<int> levels = inav_test_symbols({1, 2, 3, 4, 5, 3, 4});
  // Page 2 (word 3): a quarter of its even part's FEC symbols inverted, beyond correction.
  std::mt19937_64 rng(6);
  for (int k = 0; k < 60; ++k) {
    const auto i = static_cast<std::size_t>(2 * 500 + 10 + static_cast<int>(rng() % 240));
    levels[i] = -levels[i];
  }
  // Page 3 (word 4): one CRC bit flipped before encoding; FEC delivers it faithfully.
  {
    namespace inav = galileo::inav;
    inav::NominalPage page;
    page.word = testing::inav_test_word(4, 3);
    std::array<inav::PagePartBits, 2> bits = inav::page_part_bits(page);
    bits[1][90] ^= 1;  // the odd part's CRC spans bits 82-105
    for (std::size_t part = 0; part < 2; ++part) {
      const inav::PagePartSymbols fec = inav::encode_page_part(bits[part]);
      for (int s = 0; s < inav::kPagePartSymbols; ++s)
        levels[static_cast<std::size_t>(3 * 500 + 250 * static_cast<int>(part) + 10 + s)] =
            fec[static_cast<std::size_t>(s)] ? -1 : 1;
    }
  }
  const std::vector<E1bSymbol> symbols = noisy_symbols(levels, -1.0, 0.3, 50, 7);
  InavDecoder decoder;
  // Up to the end of page 4 (word 5): words 3 and 4 were both dropped, so no ephemeris yet.
  const std::size_t end_of_page4 = 50 + 5 * 500;
  for (std::size_t k = 0; k < end_of_page4; ++k) decoder.add(symbols[k]);
  EXPECT_EQ(decoder.pages().counts().crc_failures, 2);
  EXPECT_EQ(decoder.pages().counts().pages, 3);
  EXPECT_FALSE(decoder.navigation().ephemeris().has_value());
  // Their good copies complete it.
  for (std::size_t k = end_of_page4; k < symbols.size(); ++k) decoder.add(symbols[k]);
  EXPECT_EQ(decoder.pages().counts().crc_failures, 2);
  ASSERT_TRUE(decoder.navigation().ephemeris().has_value());
  testing::expect_same_galileo_ephemeris(*decoder.navigation().ephemeris(), testing::inav_test_expected_ephemeris());
}

TEST(InavDecoder, WithholdsAnEphemerisOfAnotherSatellite) {
  const std::vector<int> levels = inav_test_symbols({1, 2, 3, 4, 5});
  InavDecoder mine(testing::kInavTestSvid), other(testing::kInavTestSvid + 1);
  const std::vector<E1bSymbol> symbols = noisy_symbols(levels, 1.0, 0.2, 20, 5);
  mine.add(symbols);
  other.add(symbols);
  EXPECT_TRUE(mine.navigation().ephemeris().has_value());
  EXPECT_EQ(other.pages().counts().pages, 5);
  EXPECT_FALSE(other.navigation().ephemeris().has_value());
}

TEST(InavDecoder, FindsNoPagesInNoise) {
  std::mt19937_64 rng(8);
  std::normal_distribution<double> noise(0.0, 1.0);
  InavDecoder decoder;
  for (std::int64_t k = 0; k < 5000; ++k) decoder.add(E1bSymbol{noise(rng), k * kSamplesPerSymbol, k, false});
  EXPECT_EQ(decoder.pages().counts().pages, 0);
  EXPECT_FALSE(decoder.navigation().time_mark().has_value());
}

TEST(InavDecoder, DecodesTheEphemerisFromATrackedE1Channel) {
  // Pages 0-5 (words 0, 1-5); the signal starts 150 symbols before page 1, so the channel
  // has pulled in and synchronised before page 1's sync pattern.
  const std::vector<int> levels = inav_test_symbols({0, 1, 2, 3, 4, 5});
  constexpr int kFirstSymbol = 350;
  testing::E1SignalSpec spec;
  spec.code0_chips = 0.0;  // the signal's code period p carries symbol kFirstSymbol + p
  spec.symbol = [&levels](std::int64_t p) {
    const auto k = static_cast<std::size_t>(p + kFirstSymbol);
    return k < levels.size() ? levels[k] : 1;
  };
  testing::E1Signal signal(spec);
  E1TrackingConfig cfg;
  cfg.sample_rate_hz = spec.fs_hz;
  E1ChannelStart start;
  start.satellite = SatelliteId{GnssSystem::galileo, spec.prn};
  start.code_phase_chips = 0.05;
  start.doppler_hz = spec.doppler0_hz + 20.0;
  E1TrackingChannel channel(cfg, start);
  E1LoopController loops(start.doppler_hz);
  ASSERT_EQ(spec.prn, testing::kInavTestSvid);
  InavDecoder decoder(spec.prn);
  const int blocks = (static_cast<int>(levels.size()) - kFirstSymbol) * 4 / 10 + 5;
  for (int b = 0; b < blocks; ++b) {
    channel.process(signal.next(10), [&](const E1CorrelatorEpoch& e) {
      channel.apply(loops.update(e));
      decoder.add(e.symbols);
    });
  }
  ASSERT_EQ(channel.state(), E1ChannelState::tracking);
  EXPECT_EQ(decoder.pages().counts().crc_failures, 0);
  EXPECT_GE(decoder.pages().counts().pages, 5);
  const InavNavigation& nav = decoder.navigation();
  ASSERT_TRUE(nav.ephemeris().has_value());
  testing::expect_same_galileo_ephemeris(*nav.ephemeris(), testing::inav_test_expected_ephemeris());
  // Word 5 (page 5) marks its page's start: the sample at which the signal's code period
  // 5 * 500 - kFirstSymbol began arriving, within a sample.
  ASSERT_TRUE(nav.time_mark().has_value());
  EXPECT_EQ(nav.time_mark()->tow_s, kInavTestTow0 + 10);
  const double page5_chips = (5.0 * 500 - kFirstSymbol) * galileo::kE1CodeLength_chips;
  double t = page5_chips / galileo::kE1CodeRate_cps;  // solve code_chips(t) = page5_chips
  for (int i = 0; i < 4; ++i)
    t += (page5_chips - signal.code_chips(t)) /
         (galileo::kE1CodeRate_cps * (1.0 + signal.doppler_hz(t) / galileo::kE1_Hz));
  EXPECT_NEAR(static_cast<double>(nav.time_mark()->first_sample), t * spec.fs_hz, 1.0);
}

}  // namespace
}  // namespace deepnav
