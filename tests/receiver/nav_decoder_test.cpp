#include "receiver/navdata/nav_decoder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {

lnav::LnavContent content_for(int prn, GpsTime t, NavData& nav) {
  nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  lnav::LnavContent c;
  c.eph = *nav.select(prn, t);
  c.iono = nav.iono;
  c.utc = nav.utc;
  return c;
}

/// Feeds `n_bits` LNAV bits starting at week bit `first_bit` as 20 ms epochs whose code
/// periods start at `period0`, with noise and the given polarity; returns the decoder.
NavDecoder run(const lnav::LnavContent& c, std::int64_t first_bit, int n_bits, std::int64_t period0, double polarity,
               double snr_amplitude, std::uint64_t seed) {
  NavDecoder dec(c.eph.prn, 2190);
  const auto bits = lnav::lnav_bits(c, first_bit, n_bits);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int k = 0; k < n_bits; ++k) {
    CorrelatorEpoch e;
    e.prn = c.eph.prn;
    e.integration_s = 0.02;
    e.code_period = period0 + 20 * (k + 1);
    const double s = (bits[static_cast<std::size_t>(k)] ? -1.0 : 1.0) * polarity * snr_amplitude;
    e.prompt = {s + noise(rng), noise(rng)};
    dec.add(e, period0 % 20);
  }
  return dec;
}

TEST(NavDecoder, DecodesEphemerisAndTransmitTimeInBothPolarities) {
  NavData nav;
  const GpsTime t{2190, 525600.0};
  const auto c = content_for(10, t, nav);
  // Start mid-subframe: bit index of the week at 525600 s + 2.34 s.
  const std::int64_t first_bit = static_cast<std::int64_t>(525602.34 / 0.02);
  for (double polarity : {1.0, -1.0}) {
    const NavDecoder dec = run(c, first_bit, 2000, 777, polarity, 8.0, 5);
    ASSERT_TRUE(dec.synchronised());
    ASSERT_TRUE(dec.ephemeris().has_value());
    const Ephemeris& e = *dec.ephemeris();
    EXPECT_EQ(e.prn, 10);
    EXPECT_EQ(e.week, c.eph.week);
    EXPECT_EQ(e.iode, c.eph.iode);
    EXPECT_NEAR(e.sqrt_a, c.eph.sqrt_a, 2e-6);
    EXPECT_NEAR(e.e, c.eph.e, 1.2e-10);
    EXPECT_NEAR(e.toe_s, c.eph.toe_s, 16.0);
    EXPECT_NEAR(e.af0_s, c.eph.af0_s, 5e-10);
    EXPECT_NEAR(e.m0_rad, c.eph.m0_rad, 1e-8);
    EXPECT_GE(dec.subframes_decoded(), 5);
    // Bit k starts at period 777 + 20 k and at week time (first_bit + k) * 20 ms.
    const std::int64_t k = 1500;
    const auto tx = dec.transmit_time_sow(777 + 20 * k + 3, 511.5);
    ASSERT_TRUE(tx.has_value());
    EXPECT_NEAR(*tx, (first_bit + k) * 0.02 + 3e-3 + 511.5 / 1.023e6, 1e-9);
  }
}

TEST(NavDecoder, NoiseAloneNeverSynchronises) {
  NavData nav;
  const auto c = content_for(10, GpsTime{2190, 525600.0}, nav);
  const NavDecoder dec = run(c, 26280000, 3000, 0, 1.0, 0.0, 99);
  EXPECT_FALSE(dec.ephemeris().has_value());
  EXPECT_EQ(dec.subframes_decoded(), 0);
}

}  // namespace
}  // namespace deepnav

namespace deepnav {
namespace {

TEST(NavDecoder, RandomBitStreamsNeverCrashOrYieldData) {
  // 200 seeded streams of random bits with random integration lengths: the decoder must
  // neither crash nor assemble an ephemeris out of noise.
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    std::mt19937_64 rng(seed);
    NavDecoder dec(5, 2190);
    std::int64_t period = static_cast<std::int64_t>(rng() % 1000);
    for (int k = 0; k < 1200; ++k) {
      CorrelatorEpoch e;
      const int ms = (rng() % 4 == 0) ? 1 : 20;
      period += ms;
      e.code_period = period;
      e.integration_s = ms * 1e-3;
      e.prompt = {(rng() & 1) ? 1.0 : -1.0, 0.0};
      dec.add(e, static_cast<std::int64_t>(seed % 20));
    }
    EXPECT_FALSE(dec.ephemeris().has_value()) << seed;
  }
}

}  // namespace
}  // namespace deepnav

namespace deepnav {
namespace {

/// Feeds the bits as clean 20 ms epochs from code period `period0` on.
void feed(NavDecoder& dec, const std::vector<std::uint8_t>& bits, std::int64_t period0) {
  for (std::size_t k = 0; k < bits.size(); ++k) {
    CorrelatorEpoch e;
    e.integration_s = 0.02;
    e.code_period = period0 + 20 * static_cast<std::int64_t>(k + 1);
    e.prompt = {bits[k] ? -8.0 : 8.0, 0.0};
    dec.add(e, period0 % 20);
  }
}

TEST(NavDecoder, ASubframeAtOddsWithTheChannelTimeIsNotTaken) {
  NavData nav;
  const auto c = content_for(10, GpsTime{2190, 525600.0}, nav);
  const std::int64_t first_bit = static_cast<std::int64_t>(525600.0 / 0.02);
  // The broadcast bits of each (first bit, count) stretch, one after the other.
  const auto splice = [&](std::initializer_list<std::pair<std::int64_t, int>> stretches) {
    std::vector<std::uint8_t> bits;
    for (const auto& [from, count] : stretches) {
      const auto part = lnav::lnav_bits(c, first_bit + from, count);
      bits.insert(bits.end(), part.begin(), part.end());
    }
    return bits;
  };
  // 4 subframes in order, then one subframe that parity-checks but carries the data of 53
  // subframes later (a subframe read wrong at weak signal can), then 3 more in order.
  NavDecoder dec(10, 2190);
  feed(dec, splice({{0, 1200}, {1200 + 53 * 300, 300}, {1500, 900}}), 0);
  EXPECT_EQ(dec.inconsistent_subframes(), 1);
  const auto tx = dec.transmit_time_sow(20 * 2000, 0.0);
  ASSERT_TRUE(tx.has_value());
  EXPECT_NEAR(*tx, (first_bit + 2000) * 0.02, 1e-9);  // the channel's own time kept

  // Two subframes that agree with each other outvote the anchor (it was the wrong one).
  NavDecoder dec2(10, 2190);
  feed(dec2, splice({{0, 600}, {600 + 53 * 300, 900}}), 0);
  EXPECT_EQ(dec2.inconsistent_subframes(), 1);
  const auto tx2 = dec2.transmit_time_sow(20 * 1400, 0.0);
  ASSERT_TRUE(tx2.has_value());
  EXPECT_NEAR(*tx2, (first_bit + 1400 + 53 * 300) * 0.02, 1e-9);
}

/// Week bit index of 02:00:00 on 2022-01-01 (week 2190): a frame (subframe 1) starts there.
constexpr std::int64_t kFrameBit = 525600 * 50;
/// The bit that ends subframe 3 of that frame, counted from the frame's start.
constexpr int kSubframe3LastBit = 899;

/// Feeds noiseless bits from frame bit `from` (counted from the frame start) through frame
/// bit `to` as a channel delivers them; `flip` (frame bit) is received wrong. Returns the
/// frame bit whose arrival completed the ephemeris, -1 if none did.
int frame_bit_completing_ephemeris(NavDecoder& dec, const lnav::LnavContent& c, int from, int to, double polarity,
                                   int flip = -1) {
  const auto bits = lnav::lnav_bits(c, kFrameBit + from, to - from + 1);
  for (int b = from; b <= to; ++b) {
    const bool one = bits[static_cast<std::size_t>(b - from)] != 0;
    const double soft = (one ? -1.0 : 1.0) * polarity * (b == flip ? -1.0 : 1.0);
    if (dec.add_bit(PromptBit{soft, 0, 100 + 20 * std::int64_t{b - from}})) return b;
  }
  return -1;
}

TEST(NavDecoder, ColdStartReadsTheSubframeUnderWayAtTheStart) {
  NavData nav;
  const auto c = content_for(10, GpsTime{2190, 525600.0}, nav);
  for (double polarity : {1.0, -1.0}) {
    // From 2.9 s into subframe 1 (its word 5): words 6-10 are complete, and word 6's parity
    // has word 5's last two bits. With subframes 2 and 3, the ephemeris is complete when
    // subframe 3 ends, not a frame later.
    NavDecoder dec(10, 2190);
    EXPECT_EQ(frame_bit_completing_ephemeris(dec, c, 145, 1500, polarity), kSubframe3LastBit);
    ASSERT_TRUE(dec.ephemeris().has_value());
    EXPECT_EQ(dec.ephemeris()->iode, c.eph.iode);
    EXPECT_NEAR(dec.ephemeris()->af0_s, c.eph.af0_s, 5e-10);
    EXPECT_NEAR(dec.ephemeris()->m0_rad, c.eph.m0_rad, 1e-8);
    EXPECT_FALSE(dec.week_number().has_value()) << "subframe 1 word 3 was not received";
  }
}

TEST(NavDecoder, TheFirstCompleteWordIsCheckedWithTheTwoBitsBeforeIt) {
  NavData nav;
  const auto c = content_for(10, GpsTime{2190, 525600.0}, nav);
  // Starting exactly at subframe 1 word 7 leaves its parity unknown (word 6's D29*, D30*
  // missing): the word is left out and taken from the next frame, once that frame's word 8
  // (IODC) says it belongs to the same data set.
  NavDecoder at_word(10, 2190);
  EXPECT_EQ(frame_bit_completing_ephemeris(at_word, c, 180, 1800, 1.0), 1500 + 239);
  // Two bits earlier, the word is checked and used.
  NavDecoder two_before(10, 2190);
  EXPECT_EQ(frame_bit_completing_ephemeris(two_before, c, 178, 1800, 1.0), kSubframe3LastBit);
}

TEST(NavDecoder, Word3IsCheckedWithoutTheWordBeforeIt) {
  NavData nav;
  const auto c = content_for(10, GpsTime{2190, 525600.0}, nav);
  // From subframe 1 word 3 on, nothing before it: the HOW ends in 00, so word 3's parity is
  // known in the polarity the first decoded subframe gives, and it brings the week number.
  for (double polarity : {1.0, -1.0}) {
    NavDecoder dec(10, 2100);  // a reference week 90 weeks off still resolves it
    EXPECT_EQ(frame_bit_completing_ephemeris(dec, c, 60, 1000, polarity), kSubframe3LastBit);
    ASSERT_TRUE(dec.week_number().has_value());
    EXPECT_EQ(dec.week_number()->wn10, 2190 % 1024);
    EXPECT_DOUBLE_EQ(dec.week_number()->subframe_start_sow, 525600.0);
    EXPECT_EQ(dec.ephemeris()->week, 2190);
    EXPECT_EQ(dec.ephemeris()->iodc, c.eph.iodc);
  }
}

TEST(NavDecoder, AWordFailingParityIsLeftOut) {
  NavData nav;
  const auto c = content_for(10, GpsTime{2190, 525600.0}, nav);
  // A bit of subframe 1 word 9 (af1) received wrong: the clock words come a frame later.
  NavDecoder dec(10, 2190);
  const int completed = frame_bit_completing_ephemeris(dec, c, 145, 2000, 1.0, 250);
  EXPECT_EQ(completed, 1500 + 269) << "the next frame's subframe 1 word 9";
  EXPECT_NEAR(dec.ephemeris()->af1_sps, c.eph.af1_sps, 1e-15);
}

}  // namespace
}  // namespace deepnav
