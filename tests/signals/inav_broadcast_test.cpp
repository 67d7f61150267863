// The I/NAV message of a synthesized Galileo satellite: the nominal E1-B subframe layout,
// the values of words 5, 6 and 10, and the symbol table's alignment to GST.
#include "signals/sim/inav_broadcast.hpp"

#include <gtest/gtest.h>

#include "signals/galileo/inav_page.hpp"
#include "signals/sim/satellite_selection.hpp"

namespace deepnav {
namespace {

namespace inav = galileo::inav;
const std::string kRoot = DEEPNAV_SOURCE_DIR;

struct Sample {
  NavData nav = read_rinex_nav(kRoot + "/data/gps_galileo_20220101.rnx");
  galileo::GstTime t{2190 - 1024, 592200.0};  // 2022-01-01 20:30 GST
  const galileo::GalileoEphemeris* eph = select_galileo_ephemeris(nav, 3, t);
  std::int64_t second(double tow) const { return static_cast<std::int64_t>(t.week) * 604800 + std::llround(tow); }
};

TEST(InavBroadcast, NominalSubframeLayout) {
  const Sample s;
  ASSERT_NE(s.eph, nullptr);
  // 592200 is a multiple of 60: an even subframe (words 7/8 slots dummy), then an odd one (10).
  const int even_subframe[15] = {2, 4, 6, 63, 63, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0};
  const int odd_subframe[15] = {2, 4, 6, 63, 10, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0};
  for (int slot = 0; slot < 15; ++slot) {
    EXPECT_EQ(inav::word_type(synthesized_inav_word(s.nav, *s.eph, s.second(592200.0 + 2 * slot))), even_subframe[slot])
        << "slot " << slot;
    EXPECT_EQ(inav::word_type(synthesized_inav_word(s.nav, *s.eph, s.second(592230.0 + 2 * slot))), odd_subframe[slot])
        << "slot " << slot;
  }
  EXPECT_THROW(synthesized_inav_word(s.nav, *s.eph, s.second(592201.0)), std::logic_error);
}

TEST(InavBroadcast, WordsCarryTheFileParametersAndGst) {
  const Sample s;
  const inav::IonoDelayHealthWord w5 =
      inav::decode_iono_delay_health_word(synthesized_inav_word(s.nav, *s.eph, s.second(592224.0)));
  EXPECT_EQ(w5.week, s.t.week);
  EXPECT_EQ(w5.tow_s, 592224);
  EXPECT_NEAR(w5.iono.ai0_sfu, s.nav.galileo_iono.ai0_sfu, 0.25);
  EXPECT_NEAR(w5.bgd_e1e5b_s, s.eph->bgd_e1e5b_s, 0x1p-32);
  EXPECT_TRUE(w5.e1b.usable());
  const inav::UtcWord w6 = inav::decode_utc_word(synthesized_inav_word(s.nav, *s.eph, s.second(592204.0)));
  EXPECT_EQ(w6.tow_s, 592204);
  EXPECT_EQ(w6.utc.delta_t_ls, 18);
  EXPECT_NEAR(w6.utc.a0_s, s.nav.galileo_utc.a0_s, 0x1p-30);
  EXPECT_EQ(w6.utc.wnt, s.nav.galileo_utc.wnt % 256);
  inav::AlmanacBatch batch;
  inav::decode_almanac_word(synthesized_inav_word(s.nav, *s.eph, s.second(592238.0)), batch);
  EXPECT_NEAR(batch.ggto.a0g_s, s.nav.ggto.a0g_s, 0x1p-35);
  EXPECT_NEAR(batch.ggto.a1g_sps, s.nav.ggto.a1g_sps, 0x1p-51);
  EXPECT_EQ(batch.ggto.t0g_s, s.nav.ggto.t0g_s);
  EXPECT_EQ(batch.ggto.wn0g, s.nav.ggto.wn0g % 64);
  const inav::SpareWord w0 = inav::decode_spare_word(synthesized_inav_word(s.nav, *s.eph, s.second(592210.0)));
  EXPECT_EQ(w0.time_flag, 2);
  EXPECT_EQ(w0.tow_s, 592210);
}

TEST(InavBroadcast, SymbolTableStartsEachPageAtAnEvenGstSecond) {
  const Sample s;
  const std::int64_t page_period = s.second(592200.0) * 250;
  const InavSymbolTable table(s.nav, *s.eph, page_period - 700, page_period + 700);
  for (std::int64_t start : {page_period, page_period + 250, page_period - 500}) {
    for (int i = 0; i < inav::kSyncSymbols; ++i)
      EXPECT_EQ(table.sign_at_period(start + i), inav::kSyncPattern[static_cast<std::size_t>(i)] == 0 ? 1 : -1);
  }
  // The even part of the page at 592200 as encode_page sends it.
  inav::NominalPage page;
  page.word = synthesized_inav_word(s.nav, *s.eph, s.second(592200.0));
  const auto parts = inav::encode_page(page);
  for (int i = 0; i < inav::kPagePartTotalSymbols; ++i) {
    EXPECT_EQ(table.sign_at_period(page_period + i), parts[0][static_cast<std::size_t>(i)] == 0 ? 1 : -1);
    EXPECT_EQ(table.sign_at_period(page_period + 250 + i), parts[1][static_cast<std::size_t>(i)] == 0 ? 1 : -1);
  }
  EXPECT_THROW(table.sign_at_period(page_period + 100000), std::logic_error);
}

}  // namespace
}  // namespace deepnav
