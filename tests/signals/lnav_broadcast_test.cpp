// What a synthesized satellite broadcasts across a GPS week boundary: subframe 1's week
// number is the week each subframe is sent in, so the first subframe 1 after the boundary
// carries the new week (the ephemeris, and its toe's week, stay the same).
#include "signals/sim/lnav_broadcast.hpp"

#include <gtest/gtest.h>

#include "signals/lnav_message.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {

/// The subframe starting at absolute subframe count `g`, read back from the table's signs.
lnav::Subframe subframe_of(const LnavSignTable& table, std::int64_t g) {
  lnav::Subframe words{};
  for (int i = 0; i < lnav::kBitsPerSubframe; ++i) {
    const int bit = table.sign_of_bit(g * lnav::kBitsPerSubframe + i) < 0 ? 1 : 0;
    auto& word = words[static_cast<std::size_t>(i / lnav::kBitsPerWord)];
    word = (word << 1) | static_cast<std::uint32_t>(bit);
  }
  return words;
}

TEST(LnavBroadcast, SubframeOneRollsOverWithTheWeek) {
  const NavData nav = read_rinex_nav(DEEPNAV_SOURCE_DIR "/data/brdc0010.22n");
  Ephemeris eph = nav.ephemerides.front();
  ASSERT_EQ(eph.week, 2190);
  // Subframes 1 at 2190/604770 (the last frame of the week) and 2191/0 (the first).
  const std::int64_t last_frame = 2190LL * lnav::kTowCountsPerWeek + 100795;
  const std::int64_t first_frame = 2191LL * lnav::kTowCountsPerWeek;
  const LnavSignTable table(synthesized_lnav_content(nav, eph), last_frame * 6000, (first_frame + 5) * 6000 - 1);
  const auto before = lnav::decode_subframe(subframe_of(table, last_frame));
  const auto after = lnav::decode_subframe(subframe_of(table, first_frame));
  ASSERT_TRUE(before && after);
  ASSERT_EQ(before->tlm_how.subframe_id, 1);
  ASSERT_EQ(after->tlm_how.subframe_id, 1);
  EXPECT_EQ(before->eph.week, 2190 % 1024);
  EXPECT_EQ(after->eph.week, 2191 % 1024);
  // The same ephemeris either side: only the week number changed.
  EXPECT_EQ(before->eph.iodc, after->eph.iodc);
  EXPECT_EQ(before->eph.af0_s, after->eph.af0_s);
  EXPECT_EQ(after->tlm_how.tow_count, 1);
}

}  // namespace
}  // namespace deepnav
