#include "receiver/navdata/ephemeris_words.hpp"

#include <gtest/gtest.h>

#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {

constexpr int kWeek = 2190;
/// 02:00:00 on 2022-01-01: a frame starts at this subframe count of week 2190.
constexpr std::int64_t kFrameStart = 525600 / 6;

lnav::LnavContent content_for(int prn) {
  const NavData nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  lnav::LnavContent c;
  c.eph = *nav.select(prn, GpsTime{kWeek, 525600.0});
  c.iono = nav.iono;
  c.utc = nav.utc;
  return c;
}

/// d1..d24 of the words of the subframe a satellite sends at subframe count `k`.
lnav::SubframeData words_of(const lnav::LnavContent& c, std::int64_t k) {
  const auto sf = lnav::decode_subframe(lnav::subframe_of_week(c, k));
  EXPECT_TRUE(sf.has_value());
  return sf->data;
}

/// Adds words [first, last] (0-based) of subframe count `k`; returns whether any completed
/// or changed the ephemeris.
bool add_words(EphemerisWords& words, const lnav::LnavContent& c, std::int64_t k, int first, int last) {
  const lnav::SubframeData d = words_of(c, k);
  bool changed = false;
  for (int w = first; w <= last; ++w) changed = words.add(k, w, d[static_cast<std::size_t>(w)]) || changed;
  return changed;
}

TEST(EphemerisWords, ClockWordsAndOrbitWordsAreEnough) {
  const lnav::LnavContent c = content_for(10);
  EphemerisWords words(10, kWeek);
  EXPECT_FALSE(add_words(words, c, kFrameStart, 6, 9));  // subframe 1 words 7-10 only
  EXPECT_FALSE(add_words(words, c, kFrameStart + 1, 2, 9));
  EXPECT_TRUE(add_words(words, c, kFrameStart + 2, 2, 9));
  ASSERT_TRUE(words.ephemeris().has_value());
  const Ephemeris& e = *words.ephemeris();
  EXPECT_EQ(e.prn, 10);
  EXPECT_EQ(e.iode, c.eph.iode);
  EXPECT_EQ(e.iodc, c.eph.iodc & 0xFF);  // the 2 MSBs are in the word 3 not received
  EXPECT_EQ(e.week, kWeek);              // the reference stands in for it
  EXPECT_NEAR(e.af0_s, c.eph.af0_s, 5e-10);
  EXPECT_NEAR(e.sqrt_a, c.eph.sqrt_a, 2e-6);
  EXPECT_NEAR(e.omega0_rad, c.eph.omega0_rad, 1e-8);
  EXPECT_DOUBLE_EQ(e.transmission_time_s, 525600.0);
}

TEST(EphemerisWords, WordsOfTwoFramesCombineWhenTheirIssueOfDataAgrees) {
  const lnav::LnavContent c = content_for(10);
  EphemerisWords words(10, kWeek);
  // Frame 0 from 9 s on: subframe 2 words 6-10 (no IODE among them), subframe 3 whole
  // (IODE in word 10) and, from frame 1, subframe 1's clock and subframe 2's words 3-5.
  add_words(words, c, kFrameStart + 1, 5, 9);
  add_words(words, c, kFrameStart + 2, 0, 9);
  EXPECT_FALSE(add_words(words, c, kFrameStart + 5, 6, 9));
  EXPECT_FALSE(words.ephemeris().has_value());
  EXPECT_TRUE(add_words(words, c, kFrameStart + 6, 2, 4));
  ASSERT_TRUE(words.ephemeris().has_value());
  EXPECT_EQ(words.ephemeris()->iode, c.eph.iode);
  EXPECT_NEAR(words.ephemeris()->m0_rad, c.eph.m0_rad, 1e-8);
  EXPECT_NEAR(words.ephemeris()->toe_s, c.eph.toe_s, 16.0);
}

TEST(EphemerisWords, AMismatchedIssueOfDataIsNotCombined) {
  const lnav::LnavContent c = content_for(10);
  lnav::LnavContent uploaded = c;  // a new data set from frame 1 on
  uploaded.eph.iode = (c.eph.iode + 1) % 256;
  uploaded.eph.iodc = uploaded.eph.iode;
  uploaded.eph.m0_rad += 0.01;
  EphemerisWords words(10, kWeek);
  add_words(words, c, kFrameStart + 1, 5, 9);
  add_words(words, c, kFrameStart + 2, 0, 9);
  add_words(words, uploaded, kFrameStart + 5, 6, 9);
  EXPECT_FALSE(add_words(words, uploaded, kFrameStart + 6, 2, 4));
  EXPECT_FALSE(words.ephemeris().has_value()) << "words of two data sets must not make an ephemeris";
  // The new set alone completes once its own subframe 3 is in.
  add_words(words, uploaded, kFrameStart + 6, 5, 9);
  EXPECT_TRUE(add_words(words, uploaded, kFrameStart + 7, 2, 9));
  ASSERT_TRUE(words.ephemeris().has_value());
  EXPECT_EQ(words.ephemeris()->iode, uploaded.eph.iode);
  EXPECT_NEAR(words.ephemeris()->m0_rad, uploaded.eph.m0_rad, 1e-8);
}

TEST(EphemerisWords, AFrameWhoseIssueOfDataWordsDisagreeIsLeftOut) {
  const lnav::LnavContent c = content_for(10);
  lnav::LnavContent other = c;
  other.eph.iode = (c.eph.iode + 7) % 256;
  EphemerisWords words(10, kWeek);
  add_words(words, c, kFrameStart, 6, 9);
  add_words(words, c, kFrameStart + 1, 2, 9);
  // Subframe 3 word 10 of the same frame names another IODE: a frame is one data set, so
  // one of its words is wrong and none of the frame is used.
  add_words(words, c, kFrameStart + 2, 2, 8);
  EXPECT_FALSE(words.add(kFrameStart + 2, 9, words_of(other, kFrameStart + 2)[9]));
  EXPECT_FALSE(words.ephemeris().has_value());
}

TEST(EphemerisWords, AfterTheFirstEphemerisOnlyWholeSubframesUpdateIt) {
  const lnav::LnavContent c = content_for(10);
  lnav::LnavContent other = c;  // the same issue of data with another M0: a word noise let through
  other.eph.m0_rad += 0.01;
  EphemerisWords words(10, kWeek);
  add_words(words, c, kFrameStart, 6, 9);
  add_words(words, c, kFrameStart + 1, 2, 9);
  ASSERT_TRUE(add_words(words, c, kFrameStart + 2, 2, 9));
  // Single words of the next frame do not replace those in use...
  add_words(words, c, kFrameStart + 5, 6, 9);
  add_words(words, c, kFrameStart + 6, 2, 2);
  add_words(words, other, kFrameStart + 6, 3, 4);
  EXPECT_NEAR(words.ephemeris()->m0_rad, c.eph.m0_rad, 1e-8);
  // ...whole copies of subframes 1-3 do (and then bring subframe 1's word 3: the full IODC).
  add_words(words, other, kFrameStart + 10, 0, 9);
  add_words(words, other, kFrameStart + 11, 0, 9);
  add_words(words, other, kFrameStart + 12, 0, 9);
  EXPECT_NEAR(words.ephemeris()->m0_rad, other.eph.m0_rad, 1e-8);
  EXPECT_EQ(words.ephemeris()->iodc, c.eph.iodc);
}

}  // namespace
}  // namespace deepnav
