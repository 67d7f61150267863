#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "signals/galileo/crc24q.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/inav_page.hpp"
#include "signals/galileo/inav_words.hpp"
#include "tests/support/galileo_test_ephemeris.hpp"

namespace deepnav::galileo::inav {
namespace {

/// E01's I/NAV batch with the group delays of its word 5.
GalileoEphemeris e01() {
  GalileoEphemeris eph = deepnav::testing::e01_inav_batch();
  eph.bgd_e1e5a_s = 2.328306436539E-10;
  eph.bgd_e1e5b_s = 0.0;
  return eph;
}

IonoDelayHealthWord word5() {
  IonoDelayHealthWord w;
  w.iono = {81.25, -2.4609375E-01, 3.753662109375E-03, {false, true, false, false, true}, true};  // file's GAL
  w.bgd_e1e5a_s = 2.328306436539E-10;
  w.bgd_e1e5b_s = -4.656612873077E-10;
  w.e5b = {0, false};
  w.e1b = {static_cast<int>(SignalHealth::kInTest), true};
  w.week = 1173;
  w.tow_s = 597613;
  return w;
}

/// Signal levels of transmitted symbols: logic 0 -> +1, logic 1 -> -1.
PagePartSoftSymbols levels(const PagePartTransmission& part) {
  PagePartSoftSymbols out{};
  for (int i = 0; i < kPagePartSymbols; ++i) out[i] = part[kSyncSymbols + i] ? -1.0f : 1.0f;
  return out;
}

constexpr double kSemicircleLsb31 = 0x1p-31 * kPi;

TEST(GalileoInavWords, EphemerisWordsRoundTrip) {
  const GalileoEphemeris eph = e01();
  GalileoEphemeris back;
  for (int type = 1; type <= 4; ++type) {
    const Word w = encode_ephemeris_word(type, eph);
    EXPECT_EQ(word_type(w), type);
    EXPECT_EQ(decode_ephemeris_word(w, back), 100);
  }
  const KeplerElements &a = eph.orbit, &b = back.orbit;
  EXPECT_EQ(back.prn, 1);
  EXPECT_EQ(back.sisa_index, 107);
  EXPECT_DOUBLE_EQ(b.toe_s, a.toe_s);
  EXPECT_DOUBLE_EQ(back.toc_s, eph.toc_s);
  EXPECT_NEAR(b.m0_rad, a.m0_rad, kSemicircleLsb31 / 2);
  EXPECT_NEAR(b.omega0_rad, a.omega0_rad, kSemicircleLsb31 / 2);
  EXPECT_NEAR(b.i0_rad, a.i0_rad, kSemicircleLsb31 / 2);
  EXPECT_NEAR(b.omega_rad, a.omega_rad, kSemicircleLsb31 / 2);
  EXPECT_NEAR(b.e, a.e, 0x1p-34);
  EXPECT_NEAR(b.sqrt_a, a.sqrt_a, 0x1p-20);
  EXPECT_NEAR(b.idot_radps, a.idot_radps, 0x1p-44 * kPi);
  EXPECT_NEAR(b.omega_dot_radps, a.omega_dot_radps, 0x1p-44 * kPi);
  EXPECT_NEAR(b.delta_n_radps, a.delta_n_radps, 0x1p-44 * kPi);
  EXPECT_NEAR(b.cuc_rad, a.cuc_rad, 0x1p-30);
  EXPECT_NEAR(b.cus_rad, a.cus_rad, 0x1p-30);
  EXPECT_NEAR(b.cic_rad, a.cic_rad, 0x1p-30);
  EXPECT_NEAR(b.cis_rad, a.cis_rad, 0x1p-30);
  EXPECT_NEAR(b.crc_m, a.crc_m, 0x1p-6);
  EXPECT_NEAR(b.crs_m, a.crs_m, 0x1p-6);
  EXPECT_NEAR(back.af0_s, eph.af0_s, 0x1p-35);
  EXPECT_NEAR(back.af1_sps, eph.af1_sps, 0x1p-47);
  EXPECT_DOUBLE_EQ(back.af2_sps2, 0.0);
  EXPECT_THROW(encode_ephemeris_word(5, eph), std::invalid_argument);
}

TEST(GalileoInavWords, FieldsKnowTheirPlace) {
  // Word 1: type 000001, IODnav 100 = 0001100100, t0e 597600/60 = 9960 = 10011011101000.
  const Word w = encode_ephemeris_word(1, e01());
  std::string head;
  for (int i = 0; i < 30; ++i) head += static_cast<char>('0' + w[i]);
  EXPECT_EQ(head,
            "000001"
            "0001100100"
            "10011011101000");
  // Word 5's GST: WN in bits 74..85, TOW in 86..105.
  const Word w5 = encode_iono_delay_health_word(word5());
  int week = 0, tow = 0;
  for (int i = 73; i < 85; ++i) week = week * 2 + w5[i];
  for (int i = 85; i < 105; ++i) tow = tow * 2 + w5[i];
  EXPECT_EQ(week, 1173);
  EXPECT_EQ(tow, 597613);
}

TEST(GalileoInavWords, IonoDelayHealthAndGstRoundTrip) {
  const IonoDelayHealthWord in = word5();
  const IonoDelayHealthWord out = decode_iono_delay_health_word(encode_iono_delay_health_word(in));
  EXPECT_DOUBLE_EQ(out.iono.ai0_sfu, 81.25);
  EXPECT_DOUBLE_EQ(out.iono.ai1_sfu_per_deg, -2.4609375E-01);
  EXPECT_DOUBLE_EQ(out.iono.ai2_sfu_per_deg2, 3.753662109375E-03);
  EXPECT_EQ(out.iono.region_disturbed, in.iono.region_disturbed);
  EXPECT_NEAR(out.bgd_e1e5a_s, in.bgd_e1e5a_s, 0x1p-33);
  EXPECT_NEAR(out.bgd_e1e5b_s, in.bgd_e1e5b_s, 0x1p-33);
  EXPECT_EQ(out.e1b.health, 3);
  EXPECT_TRUE(out.e1b.data_invalid);
  EXPECT_TRUE(out.e5b.usable());
  EXPECT_EQ(out.week, 1173);
  EXPECT_EQ(out.tow_s, 597613);
}

TEST(GalileoInavWords, UtcSpareAndDummyWordsRoundTrip) {
  UtcWord u;
  u.utc = {-9.3132257462E-10, 8.881784197E-16, 0, 2198 % 256, 18, 137, 7, 18, true};
  u.tow_s = 12345;
  const UtcWord v = decode_utc_word(encode_utc_word(u));
  EXPECT_NEAR(v.utc.a0_s, u.utc.a0_s, 0x1p-31);
  EXPECT_NEAR(v.utc.a1_sps, u.utc.a1_sps, 0x1p-51);
  EXPECT_EQ(v.utc.delta_t_ls, 18);
  EXPECT_EQ(v.utc.tot_s, 0);
  EXPECT_EQ(v.utc.wnt, 2198 % 256);
  EXPECT_EQ(v.utc.wn_lsf, 137);
  EXPECT_EQ(v.utc.dn, 7);
  EXPECT_EQ(v.utc.delta_t_lsf, 18);
  EXPECT_EQ(v.tow_s, 12345);
  const SpareWord s = decode_spare_word(encode_spare_word({2, 1174, 3601}));
  EXPECT_EQ(s.time_flag, 2);
  EXPECT_EQ(s.week, 1174);
  EXPECT_EQ(s.tow_s, 3601);
  EXPECT_EQ(word_type(encode_dummy_word()), kDummyWordType);
  EXPECT_THROW(decode_utc_word(encode_spare_word({})), std::invalid_argument);
}

TEST(GalileoInavWords, AlmanacAndGgtoRoundTrip) {
  AlmanacBatch in;
  in.iod_a = 9;
  in.week = 2;
  in.t0a_s = 600 * 1000;
  for (int i = 0; i < 3; ++i) {
    AlmanacEntry& a = in.sv[static_cast<std::size_t>(i)];
    a.svid = 10 + i;
    a.delta_sqrt_a = -0.5 + 0.125 * i;
    a.e = 0x1p-16 * (20 + i);
    a.omega_rad = 0x1p-15 * kPi * (1000 - 300 * i);
    a.delta_i_rad = 0x1p-14 * kPi * (-7 + i);
    a.omega0_rad = 0x1p-15 * kPi * (-20000 + 17 * i);
    a.omega_dot_radps = 0x1p-33 * kPi * (-600 + i);
    a.m0_rad = 0x1p-15 * kPi * (3000 * i - 2);
    a.af0_s = 0x1p-19 * (-100 + i);
    a.af1_sps = 0x1p-38 * (5 - i);
    a.e5b_health = i;
    a.e1b_health = 3 - i;
  }
  in.ggto = {5.908e-09, 3.552713679E-15, 86400, 2198 % 64, true};
  AlmanacBatch out;
  for (int type = 7; type <= 10; ++type) decode_almanac_word(encode_almanac_word(type, in), out);
  EXPECT_EQ(out.iod_a, 9);
  EXPECT_EQ(out.week, 2);
  EXPECT_EQ(out.t0a_s, 600000);
  for (std::size_t i = 0; i < 3; ++i) {
    const AlmanacEntry &a = in.sv[i], &b = out.sv[i];
    EXPECT_EQ(b.svid, a.svid);
    EXPECT_DOUBLE_EQ(b.delta_sqrt_a, a.delta_sqrt_a);
    EXPECT_DOUBLE_EQ(b.e, a.e);
    EXPECT_DOUBLE_EQ(b.omega_rad, a.omega_rad);
    EXPECT_DOUBLE_EQ(b.delta_i_rad, a.delta_i_rad);
    EXPECT_DOUBLE_EQ(b.omega0_rad, a.omega0_rad);
    EXPECT_DOUBLE_EQ(b.omega_dot_radps, a.omega_dot_radps);
    EXPECT_DOUBLE_EQ(b.m0_rad, a.m0_rad);
    EXPECT_DOUBLE_EQ(b.af0_s, a.af0_s);
    EXPECT_DOUBLE_EQ(b.af1_sps, a.af1_sps);
    EXPECT_EQ(b.e5b_health, a.e5b_health);
    EXPECT_EQ(b.e1b_health, a.e1b_health);
  }
  EXPECT_TRUE(out.ggto.valid);
  EXPECT_NEAR(out.ggto.a0g_s, 5.908e-09, 0x1p-36);
  EXPECT_DOUBLE_EQ(out.ggto.a1g_sps, 3.552713679E-15 - std::fmod(3.552713679E-15, 0x1p-51));
  EXPECT_EQ(out.ggto.t0g_s, 86400);
  EXPECT_EQ(out.ggto.wn0g, 2198 % 64);
}

TEST(GalileoInavWords, ValuesOutsideTheirFieldAreRejectedByName) {
  GalileoEphemeris eph = e01();
  eph.orbit.crs_m = 2000.0;  // 16 bits of 1/32 m reach 1024 m
  try {
    encode_ephemeris_word(3, eph);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Crs = 2000"), std::string::npos) << e.what();
  }
  eph = e01();
  eph.orbit.e = -0.1;
  EXPECT_THROW(encode_ephemeris_word(1, eph), std::invalid_argument);
  IonoDelayHealthWord w = word5();
  w.week = 4096;  // 12 bits
  EXPECT_THROW(encode_iono_delay_health_word(w), std::invalid_argument);
}

TEST(GalileoInavWords, AssemblerWaitsForOneIodnavAndWord5) {
  const GalileoEphemeris eph = e01();
  EphemerisAssembler assembler;
  for (int type = 1; type <= 3; ++type) assembler.add(encode_ephemeris_word(type, eph));
  assembler.add(encode_iono_delay_health_word(word5()));
  EXPECT_FALSE(assembler.ephemeris());
  GalileoEphemeris other_batch = eph;
  other_batch.iod_nav = 101;
  assembler.add(encode_ephemeris_word(4, other_batch));
  EXPECT_FALSE(assembler.ephemeris());  // word 4 of another batch
  assembler.add(encode_ephemeris_word(4, eph));
  const auto out = assembler.ephemeris();
  ASSERT_TRUE(out);
  EXPECT_EQ(out->iod_nav, 100);
  EXPECT_EQ(out->prn, 1);
  EXPECT_EQ(out->week, 1173);
  EXPECT_NEAR(out->bgd_e1e5b_s, -4.656612873077E-10, 1e-20);
  EXPECT_FALSE(out->healthy_on_e1b());  // word 5 said "in test"
  // toe at the start of a week, word 5 sent at the end of the week before.
  GalileoEphemeris next = eph;
  next.orbit.toe_s = 0.0;
  next.toc_s = 0.0;
  EphemerisAssembler at_rollover;
  for (int type = 1; type <= 4; ++type) at_rollover.add(encode_ephemeris_word(type, next));
  at_rollover.add(encode_iono_delay_health_word(word5()));
  EXPECT_EQ(at_rollover.ephemeris()->week, 1174);
}

TEST(GalileoInavPage, PartsCarryTheWordAndTheCrc) {
  NominalPage page;
  page.word = encode_ephemeris_word(2, e01());
  page.odd = {0x12'3456'789AULL, 0x2A'AAAA, 1, 0xC3};
  const auto parts = page_part_bits(page);
  EXPECT_EQ(parts[0][0], 0);  // even
  EXPECT_EQ(parts[1][0], 1);  // odd
  EXPECT_EQ(parts[0][1], 0);  // nominal
  for (int i = 0; i < 112; ++i) EXPECT_EQ(parts[0][2 + i], page.word[i]) << i;
  for (int i = 0; i < 16; ++i) EXPECT_EQ(parts[1][2 + i], page.word[112 + i]) << i;
  // The 196 covered bits followed by the CRC leave no remainder.
  std::vector<std::uint8_t> covered(parts[0].begin(), parts[0].end());
  covered.insert(covered.end(), parts[1].begin(), parts[1].begin() + 106);
  EXPECT_EQ(crc24q(covered), 0u);
  page.odd.sar = 1u << 22;  // 23 bits
  EXPECT_THROW(page_part_bits(page), std::invalid_argument);
}

TEST(GalileoInavPage, TransmissionIsSyncThenFecSymbols) {
  NominalPage page;
  page.word = encode_dummy_word();
  const auto tx = encode_page(page);
  const auto parts = page_part_bits(page);
  for (int p = 0; p < 2; ++p) {
    for (int i = 0; i < kSyncSymbols; ++i) EXPECT_EQ(tx[p][i], kSyncPattern[i]);
    const PagePartSymbols fec = encode_page_part(parts[p]);
    for (int i = 0; i < kPagePartSymbols; ++i) EXPECT_EQ(tx[p][kSyncSymbols + i], fec[i]);
  }
  EXPECT_EQ(kPagePartTotalSymbols / kE1bSymbolRate_sps, 1.0);  // one second a part
}

TEST(GalileoInavPage, EncodeDecodeRoundTripForEveryWordType) {
  const GalileoEphemeris eph = e01();
  std::vector<Word> words;
  for (int type = 1; type <= 4; ++type) words.push_back(encode_ephemeris_word(type, eph));
  words.push_back(encode_iono_delay_health_word(word5()));
  words.push_back(encode_utc_word({}));
  AlmanacBatch batch;
  for (int type = 7; type <= 10; ++type) words.push_back(encode_almanac_word(type, batch));
  words.push_back(encode_spare_word({2, 1174, 100}));
  words.push_back(encode_dummy_word());
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 0.5f);
  for (const Word& w : words) {
    NominalPage page;
    page.word = w;
    page.odd.reserved1 = rng() & 0xFFFFFFFFFFULL;
    page.odd.reserved2 = rng() & 0xFF;
    const auto tx = encode_page(page);
    PagePartSoftSymbols even = levels(tx[0]), odd = levels(tx[1]);
    for (auto& s : even) s += noise(rng);
    for (auto& s : odd) s += noise(rng);
    const DecodedPage rx = decode_page(even, odd);
    EXPECT_TRUE(rx.crc_ok) << "word type " << word_type(w);
    EXPECT_TRUE(rx.parts_in_order);
    EXPECT_FALSE(rx.page.alert);
    EXPECT_EQ(rx.page.word, w) << "word type " << word_type(w);
    EXPECT_EQ(rx.page.odd.reserved1, page.odd.reserved1);
    EXPECT_EQ(rx.page.odd.reserved2, page.odd.reserved2);
  }
  // The parts swapped: the flags say so (and the CRC fails).
  NominalPage page;
  page.word = words[0];
  const auto tx = encode_page(page);
  const DecodedPage swapped = decode_page(levels(tx[1]), levels(tx[0]));
  EXPECT_FALSE(swapped.parts_in_order);
  EXPECT_FALSE(swapped.crc_ok);
}

TEST(GalileoInavPage, CorruptedPageFailsTheCrc) {
  NominalPage page;
  page.word = encode_ephemeris_word(1, e01());
  auto parts = page_part_bits(page);
  // One word bit changed after the CRC was computed, in either part: what a decoding error
  // that the FEC did not catch looks like.
  for (int part : {0, 1}) {
    auto bad = parts;
    bad[static_cast<std::size_t>(part)][10] ^= 1;
    PagePartSoftSymbols even{}, odd{};
    const PagePartSymbols se = encode_page_part(bad[0]), so = encode_page_part(bad[1]);
    for (int i = 0; i < kPagePartSymbols; ++i) even[i] = se[i] ? -1.0f : 1.0f, odd[i] = so[i] ? -1.0f : 1.0f;
    const DecodedPage rx = decode_page(even, odd);
    EXPECT_FALSE(rx.crc_ok) << "part " << part;
  }
  // A channel beyond the code's reach: the CRC catches what the decoder gets wrong.
  std::mt19937 rng(9);
  std::normal_distribution<float> noise(0.0f, 2.0f);
  const auto tx = encode_page(page);
  int failures = 0;
  for (int trial = 0; trial < 20; ++trial) {
    PagePartSoftSymbols even = levels(tx[0]), odd = levels(tx[1]);
    for (auto& s : even) s += noise(rng);
    for (auto& s : odd) s += noise(rng);
    const DecodedPage rx = decode_page(even, odd);
    if (rx.page.word != page.word) {
      EXPECT_FALSE(rx.crc_ok) << "trial " << trial;
    }
    failures += !rx.crc_ok;
  }
  EXPECT_GT(failures, 10);
}

}  // namespace
}  // namespace deepnav::galileo::inav
