// The mixed GPS + Galileo navigation file: Galileo records moved by whole weeks, written as
// RINEX 3.04 and read back equal, and data/gps_galileo_20220101.rnx as committed.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/nav_merge.hpp"
#include "signals/rinex_nav.hpp"
#include "tests/support/galileo_test_ephemeris.hpp"

namespace deepnav {
namespace {

const std::string kRoot = DEEPNAV_SOURCE_DIR;

NavData merged_sample() {
  NavMergeRequest request;
  request.galileo_week_shift = -7;
  return merge_gps_galileo(read_rinex_nav(kRoot + "/data/brdc0010.22n"),
                           read_rinex_nav(kRoot + "/data/galileo_20220220.rnx"), request);
}

std::string written(const NavData& nav) {
  std::ostringstream out;
  write_rinex3_nav(out, nav, "deepnav nav merge");
  return out.str();
}

TEST(NavMerge, MovesGalileoWeeksOnlyAndKeepsInav) {
  const NavData gal = read_rinex_nav(kRoot + "/data/galileo_20220220.rnx");
  const NavData merged = merged_sample();
  const NavData gps = read_rinex_nav(kRoot + "/data/brdc0010.22n");
  EXPECT_EQ(merged.ephemerides.size(), gps.ephemerides.size());
  ASSERT_FALSE(merged.galileo_ephemerides.empty());
  std::size_t inav = 0;
  for (const auto& eph : gal.galileo_ephemerides) inav += from_e1b_inav(eph) ? 1 : 0;
  EXPECT_EQ(merged.galileo_ephemerides.size(), inav);
  std::size_t j = 0;
  for (const auto& eph : gal.galileo_ephemerides) {
    if (!from_e1b_inav(eph)) continue;
    const auto& moved = merged.galileo_ephemerides[j++];
    EXPECT_EQ(moved.week, eph.week - 7);
    EXPECT_EQ(moved.orbit.toe_s, eph.orbit.toe_s);
    EXPECT_EQ(moved.toc_s, eph.toc_s);
    EXPECT_EQ(moved.transmission_time_s, eph.transmission_time_s);
    // Same ECEF position at the same second of week, seven weeks earlier.
    const galileo::GstTime t{eph.week, eph.orbit.toe_s + 600.0};
    const auto a = galileo::satellite_state(eph, t);
    const auto b = galileo::satellite_state(moved, galileo::GstTime{t.week - 7, t.tow_s});
    EXPECT_LT((a.r_ecef_m - b.r_ecef_m).norm(), 1e-6);
  }
  EXPECT_EQ(merged.ggto.wn0g, gal.ggto.wn0g - 7);
  EXPECT_EQ(merged.ggto.t0g_s, gal.ggto.t0g_s);
  EXPECT_EQ(merged.galileo_utc.wnt, gal.galileo_utc.wnt - 7);
  // GST week 1166 is GPS week 2190, the week of 2022-01-01.
  EXPECT_EQ(merged.galileo_ephemerides.front().week, 2190 - 1024);
}

TEST(NavMerge, WrittenMixedFileReadsBackEqual) {
  const NavData merged = merged_sample();
  const std::string text = written(merged);
  EXPECT_NE(text.find("M: MIXED"), std::string::npos);
  EXPECT_NE(text.find("GAL "), std::string::npos);
  EXPECT_NE(text.find("GAGP"), std::string::npos);
  EXPECT_NE(text.find("GAUT"), std::string::npos);
  std::istringstream in(text);
  const NavData back = read_rinex_nav(in, "written");
  ASSERT_EQ(back.galileo_ephemerides.size(), merged.galileo_ephemerides.size());
  for (std::size_t i = 0; i < back.galileo_ephemerides.size(); ++i)
    testing::expect_same_galileo_ephemeris(back.galileo_ephemerides[i], merged.galileo_ephemerides[i]);
  ASSERT_EQ(back.ephemerides.size(), merged.ephemerides.size());
  EXPECT_EQ(back.galileo_iono.ai0_sfu, merged.galileo_iono.ai0_sfu);
  EXPECT_EQ(back.galileo_iono.ai1_sfu_per_deg, merged.galileo_iono.ai1_sfu_per_deg);
  EXPECT_EQ(back.ggto.a0g_s, merged.ggto.a0g_s);
  EXPECT_EQ(back.ggto.a1g_sps, merged.ggto.a1g_sps);
  EXPECT_EQ(back.ggto.wn0g, merged.ggto.wn0g);
  EXPECT_EQ(back.galileo_utc.a0_s, merged.galileo_utc.a0_s);
  EXPECT_EQ(back.galileo_utc.wnt, merged.galileo_utc.wnt);
  // GPUT's A0 is written with the 11 digits RINEX 3 gives it; RINEX 2's DELTA-UTC had more.
  EXPECT_NEAR(back.utc.a0_s, merged.utc.a0_s, 1e-19);
  // Written again: the same bytes.
  EXPECT_EQ(written(back), text);
}

TEST(NavMerge, GalileoOnlyFileIsTypeE) {
  NavData gal = read_rinex_nav(kRoot + "/data/galileo_20220220.rnx");
  const std::string text = written(gal);
  EXPECT_NE(text.find("E: GALILEO"), std::string::npos);
  std::istringstream in(text);
  EXPECT_EQ(read_rinex_nav(in, "written").galileo_ephemerides.size(), gal.galileo_ephemerides.size());
}

TEST(NavMerge, CommittedFileIsTheMergeOfTheTwoFiles) {
  std::ifstream in(kRoot + "/data/gps_galileo_20220101.rnx");
  ASSERT_TRUE(in) << "data/gps_galileo_20220101.rnx missing";
  std::ostringstream committed;
  committed << in.rdbuf();
  EXPECT_EQ(committed.str(), written(merged_sample()));
}

TEST(NavMerge, ErrorsNameTheFile) {
  const NavData gps = read_rinex_nav(kRoot + "/data/brdc0010.22n");
  const NavData gal = read_rinex_nav(kRoot + "/data/galileo_20220220.rnx");
  try {
    merge_gps_galileo(gal, gal, {});
    FAIL() << "a Galileo file as the GPS input was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("galileo_20220220.rnx"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no GPS record"), std::string::npos) << e.what();
  }
  try {
    merge_gps_galileo(gps, gps, {});
    FAIL() << "a GPS file as the Galileo input was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("brdc0010.22n"), std::string::npos) << e.what();
  }
  NavMergeRequest far;
  far.galileo_week_shift = -5000;
  EXPECT_THROW(merge_gps_galileo(gps, gal, far), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
