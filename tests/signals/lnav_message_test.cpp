#include "signals/lnav_message.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "signals/gps_constants.hpp"
#include "signals/lnav_parity.hpp"

namespace deepnav::lnav {
namespace {

constexpr double kSc = gps::kPi;  // semicircle in radians

// PRN 1 of data/brdc0010.22n (2022-01-01 00:00 GPS, week 2190).
Ephemeris real_ephemeris_prn1() {
  Ephemeris e;
  e.prn = 1;
  e.week = 2190;
  e.iodc = 39;
  e.iode = 39;
  e.health = 0;
  e.ura_index = 0;
  e.code_on_l2 = 1;
  e.l2p_data_flag = 0;
  e.fit_interval_flag = 0;
  e.toc_s = 518400.0;
  e.af0_s = 0.469126738608e-03;
  e.af1_sps = -0.100044417195e-10;
  e.af2_sps2 = 0.0;
  e.tgd_s = 0.512227416039e-08;
  e.crs_m = -0.141125000000e+03;
  e.delta_n_radps = 0.398838041777e-08;
  e.m0_rad = -0.624294238235e+00;
  e.cuc_rad = -0.736303627491e-05;
  e.e = 0.112181392033e-01;
  e.cus_rad = 0.469572842121e-05;
  e.sqrt_a = 0.515367499542e+04;
  e.toe_s = 518400.0;
  e.cic_rad = -0.316649675369e-07;
  e.omega0_rad = -0.103661124009e+01;
  e.cis_rad = 0.195577740669e-06;
  e.i0_rad = 0.986418769490e+00;
  e.crc_m = 0.299750000000e+03;
  e.omega_rad = 0.884087601569e+00;
  e.omega_dot_radps = -0.813355308085e-08;
  e.idot_radps = -0.377872882780e-09;
  return e;
}

// Every field at the most negative (or zero) value its bit field holds.
Ephemeris minimum_ephemeris() {
  Ephemeris e;
  e.prn = 32;
  e.week = 1024;  // WN 0
  e.iodc = 0;
  e.iode = 0;
  e.health = 0;
  e.ura_index = 0;
  e.code_on_l2 = 0;
  e.toc_s = 0.0;
  e.tgd_s = -128 * 0x1p-31;
  e.af2_sps2 = -128 * 0x1p-55;
  e.af1_sps = -32768 * 0x1p-43;
  e.af0_s = -(1 << 21) * 0x1p-31;
  e.crs_m = -32768 * 0x1p-5;
  e.delta_n_radps = -32768 * 0x1p-43 * kSc;
  e.m0_rad = -0x1p31 * 0x1p-31 * kSc;
  e.cuc_rad = -32768 * 0x1p-29;
  e.e = 0.0;
  e.cus_rad = -32768 * 0x1p-29;
  e.sqrt_a = 0.0;
  e.toe_s = 0.0;
  e.cic_rad = -32768 * 0x1p-29;
  e.omega0_rad = -kSc;
  e.cis_rad = -32768 * 0x1p-29;
  e.i0_rad = -kSc;
  e.crc_m = -32768 * 0x1p-5;
  e.omega_rad = -kSc;
  e.omega_dot_radps = -(1 << 23) * 0x1p-43 * kSc;
  e.idot_radps = -8192 * 0x1p-43 * kSc;
  e.aodo_s = 0.0;
  return e;
}

// Every field at the largest value its bit field holds.
Ephemeris maximum_ephemeris() {
  Ephemeris e;
  e.prn = 31;
  e.week = 2047;  // WN 1023
  e.iodc = 1023;
  e.iode = 255;
  e.health = 63;
  e.ura_index = 15;
  e.code_on_l2 = 3;
  e.l2p_data_flag = 1;
  e.fit_interval_flag = 1;
  e.toc_s = 65535 * 16.0;  // beyond a week, but the 16-bit field holds it
  e.tgd_s = 127 * 0x1p-31;
  e.af2_sps2 = 127 * 0x1p-55;
  e.af1_sps = 32767 * 0x1p-43;
  e.af0_s = ((1 << 21) - 1) * 0x1p-31;
  e.crs_m = 32767 * 0x1p-5;
  e.delta_n_radps = 32767 * 0x1p-43 * kSc;
  e.m0_rad = (0x1p31 - 1) * 0x1p-31 * kSc;
  e.cuc_rad = 32767 * 0x1p-29;
  e.e = (0x1p32 - 1) * 0x1p-33;
  e.cus_rad = 32767 * 0x1p-29;
  e.sqrt_a = (0x1p32 - 1) * 0x1p-19;
  e.toe_s = 604784.0;
  e.cic_rad = 32767 * 0x1p-29;
  e.omega0_rad = (0x1p31 - 1) * 0x1p-31 * kSc;
  e.cis_rad = 32767 * 0x1p-29;
  e.i0_rad = (0x1p31 - 1) * 0x1p-31 * kSc;
  e.crc_m = 32767 * 0x1p-5;
  e.omega_rad = (0x1p31 - 1) * 0x1p-31 * kSc;
  e.omega_dot_radps = ((1 << 23) - 1) * 0x1p-43 * kSc;
  e.idot_radps = 8191 * 0x1p-43 * kSc;
  e.aodo_s = 31 * 900.0;
  return e;
}

LnavContent content_with(const Ephemeris& eph) {
  LnavContent c;
  c.eph = eph;
  c.iono.alpha = {0.1211e-07, -0.7451e-08, -0.5960e-07, 0.1192e-06};
  c.iono.beta = {0.1167e+06, -0.2458e+06, -0.6554e+05, 0.1114e+07};
  c.iono.valid = true;
  c.utc.a0_s = 0.279396772385e-08;
  c.utc.a1_sps = 0.799360577730e-14;
  c.utc.tot_s = 147456;
  c.utc.wnt = 2191 & 0xFF;
  c.utc.delta_t_ls = 18;
  c.utc.wn_lsf = 2185 & 0xFF;
  c.utc.dn = 7;
  c.utc.delta_t_lsf = 18;
  c.utc.valid = true;
  c.tlm_message = 0x2A5B;
  c.integrity_flag = true;
  c.anti_spoof = true;
  c.almanac_week = eph.week;
  return c;
}

// Checks every subframe 1-3 field to within half an LSB of the message.
void expect_ephemeris_fields_near(const Ephemeris& got, const Ephemeris& want) {
  EXPECT_EQ(got.iodc, want.iodc);
  EXPECT_EQ(got.iode, want.iode);
  EXPECT_EQ(got.health, want.health);
  EXPECT_EQ(got.ura_index, want.ura_index);
  EXPECT_EQ(got.code_on_l2, want.code_on_l2);
  EXPECT_EQ(got.l2p_data_flag, want.l2p_data_flag);
  EXPECT_EQ(got.fit_interval_flag, want.fit_interval_flag);
  auto near = [](double g, double w, double lsb, const char* name) {
    EXPECT_LE(std::abs(g - w), 0.5 * lsb * (1 + 1e-9)) << name << ": got " << g << " want " << w;
  };
  near(got.toc_s, want.toc_s, 16, "toc");
  near(got.tgd_s, want.tgd_s, 0x1p-31, "TGD");
  near(got.af2_sps2, want.af2_sps2, 0x1p-55, "af2");
  near(got.af1_sps, want.af1_sps, 0x1p-43, "af1");
  near(got.af0_s, want.af0_s, 0x1p-31, "af0");
  near(got.crs_m, want.crs_m, 0x1p-5, "Crs");
  near(got.delta_n_radps, want.delta_n_radps, 0x1p-43 * kSc, "delta n");
  near(got.m0_rad, want.m0_rad, 0x1p-31 * kSc, "M0");
  near(got.cuc_rad, want.cuc_rad, 0x1p-29, "Cuc");
  near(got.e, want.e, 0x1p-33, "e");
  near(got.cus_rad, want.cus_rad, 0x1p-29, "Cus");
  near(got.sqrt_a, want.sqrt_a, 0x1p-19, "sqrt A");
  near(got.toe_s, want.toe_s, 16, "toe");
  near(got.aodo_s, want.aodo_s, 900, "AODO");
  near(got.cic_rad, want.cic_rad, 0x1p-29, "Cic");
  near(got.omega0_rad, want.omega0_rad, 0x1p-31 * kSc, "OMEGA0");
  near(got.cis_rad, want.cis_rad, 0x1p-29, "Cis");
  near(got.i0_rad, want.i0_rad, 0x1p-31 * kSc, "i0");
  near(got.crc_m, want.crc_m, 0x1p-5, "Crc");
  near(got.omega_rad, want.omega_rad, 0x1p-31 * kSc, "omega");
  near(got.omega_dot_radps, want.omega_dot_radps, 0x1p-43 * kSc, "OMEGADOT");
  near(got.idot_radps, want.idot_radps, 0x1p-43 * kSc, "IDOT");
}

// The HOW TOW count of subframe 1 sent at toe (a data set is broadcast around its toe:
// WN, the week of transmission, is then toe's week).
int tow_count_at_toe(const Ephemeris& e) { return static_cast<int>(e.toe_s / 6.0) % kTowCountsPerWeek + 1; }

// Decodes subframes 1-3 of a content, sent from its toe on, and merges them the way a
// receiver does.
Ephemeris decode_ephemeris(const LnavContent& c, int reference_week) {
  EphemerisAssembler assembler(c.eph.prn, reference_week);
  for (int id = 1; id <= 3; ++id) {
    const int tow_count = (tow_count_at_toe(c.eph) + id - 1) % kTowCountsPerWeek;
    const auto sf = decode_subframe(encode_subframe(id, c, tow_count, 1));
    EXPECT_TRUE(sf.has_value()) << "subframe " << id;
    if (!sf) return {};
    EXPECT_EQ(sf->tlm_how.subframe_id, id);
    EXPECT_EQ(sf->tlm_how.tow_count, tow_count);
    EXPECT_EQ(assembler.add(*sf), id == 3);
  }
  EXPECT_TRUE(assembler.ephemeris().has_value());
  return assembler.ephemeris().value_or(Ephemeris{});
}

TEST(LnavMessage, RealEphemerisRoundTrip) {
  const auto want = real_ephemeris_prn1();
  const auto got = decode_ephemeris(content_with(want), 2200);
  expect_ephemeris_fields_near(got, want);
  EXPECT_EQ(got.prn, 1);
  EXPECT_EQ(got.week, 2190);
  EXPECT_DOUBLE_EQ(got.transmission_time_s, 6.0 * (tow_count_at_toe(want) - 1));
}

TEST(LnavMessage, ExtremeFieldValuesRoundTrip) {
  for (const auto& want : {minimum_ephemeris(), maximum_ephemeris()}) {
    const auto got = decode_ephemeris(content_with(want), want.week + 100);
    expect_ephemeris_fields_near(got, want);
    EXPECT_EQ(got.week, want.week);
  }
}

TEST(LnavMessage, RandomEphemerisFieldsRoundTrip) {
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    Ephemeris e = real_ephemeris_prn1();
    e.iodc = static_cast<int>(rng() % 1024);
    e.iode = e.iodc & 0xFF;
    e.m0_rad = u(rng) * kSc;
    e.omega0_rad = u(rng) * kSc;
    e.omega_rad = u(rng) * kSc;
    e.i0_rad = 0.3 * kSc + 0.05 * u(rng);
    e.af0_s = u(rng) * 9e-4;
    e.af1_sps = u(rng) * 3e-10;
    e.crs_m = u(rng) * 1000;
    e.crc_m = u(rng) * 1000;
    e.e = 0.03 * (u(rng) + 1) / 2;
    e.toe_s = 16.0 * static_cast<double>(rng() % 37800);
    e.toc_s = e.toe_s;
    const auto got = decode_ephemeris(content_with(e), 2190);
    expect_ephemeris_fields_near(got, e);
  }
}

TEST(LnavMessage, OutOfRangeFieldIsRejectedWithItsName) {
  auto e = real_ephemeris_prn1();
  e.af0_s = 3e-3;  // 22 bits of 2^-31 s hold +-1.95 ms
  try {
    encode_subframe(1, content_with(e), 1, 1);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("af0"), std::string::npos) << ex.what();
    EXPECT_NE(std::string(ex.what()).find("subframe 1"), std::string::npos) << ex.what();
  }
  e = real_ephemeris_prn1();
  e.e = -0.01;
  EXPECT_THROW(encode_subframe(2, content_with(e), 1, 1), std::invalid_argument);
  e = real_ephemeris_prn1();
  e.idot_radps = std::nan("");
  EXPECT_THROW(encode_subframe(3, content_with(e), 1, 1), std::invalid_argument);
  EXPECT_THROW(encode_subframe(6, content_with(e), 1, 1), std::invalid_argument);
  EXPECT_THROW(encode_subframe(4, content_with(real_ephemeris_prn1()), 1, 26), std::invalid_argument);
  EXPECT_THROW(encode_subframe(1, content_with(real_ephemeris_prn1()), kTowCountsPerWeek, 1), std::invalid_argument);
}

TEST(LnavMessage, TlmAndHowFields) {
  auto c = content_with(real_ephemeris_prn1());
  c.alert = true;
  const auto words = encode_subframe(2, c, 100799, 1);
  EXPECT_EQ(words[0] >> 22, kPreamble);  // preamble sent uncomplemented
  const auto sf = decode_subframe(words);
  ASSERT_TRUE(sf.has_value());
  EXPECT_FALSE(sf->inverted);
  EXPECT_EQ(sf->tlm_how.tlm_message, 0x2A5B);
  EXPECT_TRUE(sf->tlm_how.integrity_flag);
  EXPECT_FALSE(sf->tlm_how.tlm_reserved);
  EXPECT_EQ(sf->tlm_how.tow_count, 100799);
  EXPECT_TRUE(sf->tlm_how.alert);
  EXPECT_TRUE(sf->tlm_how.anti_spoof);
  EXPECT_EQ(sf->tlm_how.subframe_id, 2);
  // Words 2 and 10 end in D29 = D30 = 0 (t bits), so words 3 and 1 of the next subframe are
  // never complemented.
  for (int w : {1, 9}) {
    EXPECT_FALSE(word_d29(words[w]));
    EXPECT_FALSE(word_d30(words[w]));
  }
}

TEST(LnavMessage, SourceDataWordsReencodeToTheTransmittedSubframe) {
  auto c = content_with(real_ephemeris_prn1());
  c.anti_spoof = true;
  for (std::int64_t k :
       {std::int64_t{0}, std::int64_t{3}, std::int64_t{4}, std::int64_t{87612}, std::int64_t{100799}}) {
    const Subframe words = subframe_of_week(c, k);
    const auto sf = decode_subframe(words);
    ASSERT_TRUE(sf.has_value()) << k;
    EXPECT_EQ(encode_words(sf->data), words) << k;
    // d23, d24 of words 2 and 10 are recomputed from the chain, whatever the data holds there.
    SubframeData cleared = sf->data;
    cleared[1] &= ~0x3u;
    cleared[9] |= 0x3u;
    EXPECT_EQ(encode_words(cleared), words) << k;
    // TLM and HOW source data from their fields and back.
    const auto th = tlm_how_data(sf->tlm_how);
    EXPECT_EQ(th[0], sf->data[0]) << k;
    EXPECT_EQ(th[1], sf->data[1] & ~0x3u) << k;
    const TlmHow back = tlm_how_from_data(th[0], th[1]);
    EXPECT_EQ(back.tlm_message, c.tlm_message);
    EXPECT_EQ(back.tow_count, static_cast<int>((k + 1) % kTowCountsPerWeek));
    EXPECT_EQ(back.subframe_id, subframe_id_at(k));
    EXPECT_TRUE(back.anti_spoof);
    EXPECT_EQ(back.integrity_flag, c.integrity_flag);
  }
  TlmHow bad;
  bad.tow_count = kTowCountsPerWeek;
  EXPECT_THROW(tlm_how_data(bad), std::invalid_argument);
  bad.tow_count = 0;
  bad.tlm_message = 1 << 14;
  EXPECT_THROW(tlm_how_data(bad), std::invalid_argument);
}

TEST(LnavMessage, PageIdsFollowTable20V) {
  EXPECT_EQ(page_sv_id(4, 1), 57);
  EXPECT_EQ(page_sv_id(4, 2), 25);
  EXPECT_EQ(page_sv_id(4, 10), 32);
  EXPECT_EQ(page_sv_id(4, 13), 52);
  EXPECT_EQ(page_sv_id(4, 17), 55);
  EXPECT_EQ(page_sv_id(4, 18), 56);
  EXPECT_EQ(page_sv_id(4, 24), 62);
  EXPECT_EQ(page_sv_id(4, 25), 63);
  EXPECT_EQ(page_sv_id(5, 7), 7);
  EXPECT_EQ(page_sv_id(5, 25), 51);
  EXPECT_THROW(page_sv_id(3, 1), std::invalid_argument);
  EXPECT_EQ(subframe_id_at(0), 1);
  EXPECT_EQ(subframe_id_at(9), 5);
  EXPECT_EQ(page_at(4), 1);
  EXPECT_EQ(page_at(5), 2);
  EXPECT_EQ(page_at(124), 25);
  EXPECT_EQ(page_at(125), 1);
}

LnavContent content_with_almanac() {
  auto c = content_with(real_ephemeris_prn1());
  for (int prn = 1; prn <= 32; ++prn) {
    if (prn == 13 || prn == 30) continue;  // dummy SVs
    Ephemeris e = real_ephemeris_prn1();
    e.prn = prn;
    e.m0_rad = -3.0 + 0.19 * prn;
    e.omega0_rad = 3.1 - 0.2 * prn;
    e.omega_rad = -1.5 + 0.09 * prn;
    e.health = prn == 7 ? 0x21 : 0;
    e.af0_s = (prn - 16) * 3e-5;
    c.almanac[prn - 1] = almanac_from_ephemeris(e);
  }
  c.almanac_toa_s = c.almanac[0]->toa_s;
  for (int prn = 1; prn <= 32; ++prn) c.sv_config[prn - 1] = static_cast<std::uint8_t>(prn % 16);
  return c;
}

TEST(LnavMessage, AlmanacFromEphemerisIsConsistent) {
  const auto eph = real_ephemeris_prn1();
  const auto a = almanac_from_ephemeris(eph);
  EXPECT_EQ(a.prn, 1);
  EXPECT_EQ(a.toa_s % 4096, 0);
  EXPECT_LE(std::abs(a.toa_s - eph.toe_s), 2048);
  EXPECT_EQ(a.week, eph.week);
  const double dt = a.toa_s - eph.toe_s;
  EXPECT_NEAR(a.delta_i_rad + 0.3 * kSc, eph.i0_rad + eph.idot_radps * dt, 0x1p-20 * kSc);
  EXPECT_NEAR(a.sqrt_a, eph.sqrt_a, 0x1p-12);
  EXPECT_NEAR(a.e, eph.e, 0x1p-22);
  EXPECT_NEAR(a.omega0_rad, eph.omega0_rad + eph.omega_dot_radps * dt, 0x1p-24 * kSc);
  const double n = std::sqrt(gps::kGM_m3ps2 / std::pow(eph.sqrt_a, 6)) + eph.delta_n_radps;
  EXPECT_NEAR(a.m0_rad, eph.m0_rad + n * dt, 0x1p-24 * kSc);
  EXPECT_NEAR(a.af0_s, eph.af0_s + eph.af1_sps * dt, 0x1p-21);
  EXPECT_EQ(a.health, 0);
  auto sick = eph;
  sick.health = 0x21;
  EXPECT_EQ(almanac_from_ephemeris(sick).health, 0xE1);
}

TEST(LnavMessage, AlmanacPagesRoundTrip) {
  const auto c = content_with_almanac();
  int seen = 0, dummies = 0;
  // One full page cycle: 125 subframes.
  for (std::int64_t k = 0; k < 125; ++k) {
    const int id = subframe_id_at(k);
    if (id < 4) continue;
    const auto sf = decode_subframe(subframe_of_week(c, k));
    ASSERT_TRUE(sf.has_value()) << "subframe " << k;
    EXPECT_EQ(sf->page, page_at(k));
    EXPECT_EQ(sf->data_id, 1);
    const int expected_id = page_sv_id(id, page_at(k));
    if (expected_id > 32) {
      EXPECT_EQ(sf->sv_id, expected_id);
      continue;
    }
    const auto& want = c.almanac[expected_id - 1];
    if (!want) {
      EXPECT_EQ(sf->sv_id, 0) << "dummy SV page";
      EXPECT_FALSE(sf->almanac.has_value());
      ++dummies;
      continue;
    }
    ASSERT_TRUE(sf->almanac.has_value());
    const auto& got = *sf->almanac;
    ++seen;
    // almanac_from_ephemeris quantizes, so the message carries it exactly.
    EXPECT_EQ(got.prn, want->prn);
    EXPECT_EQ(got.health, want->health);
    EXPECT_EQ(got.toa_s, want->toa_s);
    EXPECT_DOUBLE_EQ(got.e, want->e);
    EXPECT_DOUBLE_EQ(got.delta_i_rad, want->delta_i_rad);
    EXPECT_DOUBLE_EQ(got.omega_dot_radps, want->omega_dot_radps);
    EXPECT_DOUBLE_EQ(got.sqrt_a, want->sqrt_a);
    EXPECT_DOUBLE_EQ(got.omega0_rad, want->omega0_rad);
    EXPECT_DOUBLE_EQ(got.omega_rad, want->omega_rad);
    EXPECT_DOUBLE_EQ(got.m0_rad, want->m0_rad);
    EXPECT_DOUBLE_EQ(got.af0_s, want->af0_s);
    EXPECT_DOUBLE_EQ(got.af1_sps, want->af1_sps);
  }
  EXPECT_EQ(seen, 30);
  EXPECT_EQ(dummies, 2);
}

TEST(LnavMessage, AlmanacExtremesRoundTripWithinOneLsb) {
  auto c = content_with(real_ephemeris_prn1());
  Almanac lo, hi;
  lo.prn = hi.prn = 5;
  lo.e = 0.0;
  hi.e = 65535 * 0x1p-21;
  lo.toa_s = 0;
  hi.toa_s = 602112;
  lo.delta_i_rad = -32768 * 0x1p-19 * kSc;
  hi.delta_i_rad = 32767 * 0x1p-19 * kSc;
  lo.omega_dot_radps = -32768 * 0x1p-38 * kSc;
  hi.omega_dot_radps = 32767 * 0x1p-38 * kSc;
  lo.sqrt_a = 0;
  hi.sqrt_a = (0x1p24 - 1) * 0x1p-11;
  lo.omega0_rad = lo.omega_rad = lo.m0_rad = -kSc;
  hi.omega0_rad = hi.omega_rad = hi.m0_rad = (0x1p23 - 1) * 0x1p-23 * kSc;
  lo.af0_s = -1024 * 0x1p-20;
  hi.af0_s = 1023 * 0x1p-20;
  lo.af1_sps = -1024 * 0x1p-38;
  hi.af1_sps = 1023 * 0x1p-38 + 0.3 * 0x1p-38;  // rounds down to the largest count
  hi.health = 255;
  for (const auto& want : {lo, hi}) {
    c.almanac[4] = want;
    const auto sf = decode_subframe(encode_subframe(5, c, 30, 5));
    ASSERT_TRUE(sf && sf->almanac);
    const auto& got = *sf->almanac;
    EXPECT_EQ(got.health, want.health);
    EXPECT_EQ(got.toa_s, want.toa_s);
    EXPECT_NEAR(got.e, want.e, 0x1p-22);
    EXPECT_NEAR(got.delta_i_rad, want.delta_i_rad, 0x1p-20 * kSc);
    EXPECT_NEAR(got.omega_dot_radps, want.omega_dot_radps, 0x1p-39 * kSc);
    EXPECT_NEAR(got.sqrt_a, want.sqrt_a, 0x1p-12);
    EXPECT_NEAR(got.omega0_rad, want.omega0_rad, 0x1p-24 * kSc);
    EXPECT_NEAR(got.omega_rad, want.omega_rad, 0x1p-24 * kSc);
    EXPECT_NEAR(got.m0_rad, want.m0_rad, 0x1p-24 * kSc);
    EXPECT_NEAR(got.af0_s, want.af0_s, 0x1p-21);
    EXPECT_NEAR(got.af1_sps, want.af1_sps, 0x1p-39);
  }
  c.almanac[4]->af0_s = 1e-3;  // beyond 11 bits of 2^-20 s
  EXPECT_THROW(encode_subframe(5, c, 30, 5), std::invalid_argument);
}

TEST(LnavMessage, IonoUtcPageRoundTrip) {
  const auto c = content_with(real_ephemeris_prn1());
  const auto sf = decode_subframe(encode_subframe(4, c, 90, 18));
  ASSERT_TRUE(sf.has_value());
  EXPECT_EQ(sf->sv_id, 56);
  ASSERT_TRUE(sf->iono && sf->utc);
  const std::array<double, 4> alpha_lsb = {0x1p-30, 0x1p-27, 0x1p-24, 0x1p-24};
  const std::array<double, 4> beta_lsb = {0x1p11, 0x1p14, 0x1p16, 0x1p16};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(sf->iono->alpha[i], c.iono.alpha[i], 0.5 * alpha_lsb[i]) << i;
    EXPECT_NEAR(sf->iono->beta[i], c.iono.beta[i], 0.5 * beta_lsb[i]) << i;
  }
  EXPECT_TRUE(sf->iono->valid);
  EXPECT_NEAR(sf->utc->a0_s, c.utc.a0_s, 0x1p-31);
  EXPECT_NEAR(sf->utc->a1_sps, c.utc.a1_sps, 0x1p-51);
  EXPECT_EQ(sf->utc->tot_s, c.utc.tot_s);
  EXPECT_EQ(sf->utc->wnt, c.utc.wnt);
  EXPECT_EQ(sf->utc->delta_t_ls, 18);
  EXPECT_EQ(sf->utc->wn_lsf, c.utc.wn_lsf);
  EXPECT_EQ(sf->utc->dn, 7);
  EXPECT_EQ(sf->utc->delta_t_lsf, 18);
  EXPECT_TRUE(sf->utc->valid);

  // Negative leap seconds and extreme A0/A1 fit their two's-complement fields.
  auto c2 = c;
  c2.utc.delta_t_ls = -128;
  c2.utc.delta_t_lsf = 127;
  c2.utc.a0_s = -0x1p31 * 0x1p-30;
  c2.utc.a1_sps = (0x1p23 - 1) * 0x1p-50;
  c2.iono.alpha = {-128 * 0x1p-30, 127 * 0x1p-27, -128 * 0x1p-24, 127 * 0x1p-24};
  const auto sf2 = decode_subframe(encode_subframe(4, c2, 90, 18));
  ASSERT_TRUE(sf2 && sf2->utc && sf2->iono);
  EXPECT_EQ(sf2->utc->delta_t_ls, -128);
  EXPECT_EQ(sf2->utc->delta_t_lsf, 127);
  EXPECT_DOUBLE_EQ(sf2->utc->a0_s, c2.utc.a0_s);
  EXPECT_DOUBLE_EQ(sf2->utc->a1_sps, c2.utc.a1_sps);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(sf2->iono->alpha[i], c2.iono.alpha[i]);

  EphemerisAssembler assembler(1, 2190);
  EXPECT_FALSE(assembler.add(*sf));
  EXPECT_TRUE(assembler.iono().valid);
  EXPECT_TRUE(assembler.utc().valid);
  EXPECT_EQ(assembler.utc().delta_t_ls, 18);
}

TEST(LnavMessage, HealthAndConfigurationPages) {
  const auto c = content_with_almanac();
  const auto p5 = decode_subframe(encode_subframe(5, c, 125, 25));
  ASSERT_TRUE(p5.has_value());
  EXPECT_EQ(p5->sv_id, 51);
  ASSERT_TRUE(p5->almanac_toa_s && p5->almanac_wna);
  EXPECT_EQ(*p5->almanac_toa_s, c.almanac_toa_s);
  EXPECT_EQ(*p5->almanac_wna, 2190 % 256);
  for (int prn = 1; prn <= 24; ++prn) {
    const int want = prn == 13 ? 0x3F : prn == 7 ? 0x21 : 0;
    EXPECT_EQ(p5->sv_health[prn - 1], want) << "PRN " << prn;
  }
  EXPECT_EQ(p5->sv_health[24], -1);

  const auto p4 = decode_subframe(encode_subframe(4, c, 125, 25));
  ASSERT_TRUE(p4.has_value());
  EXPECT_EQ(p4->sv_id, 63);
  for (int prn = 1; prn <= 32; ++prn) EXPECT_EQ(p4->sv_config[prn - 1], prn % 16) << "PRN " << prn;
  for (int prn = 25; prn <= 32; ++prn) EXPECT_EQ(p4->sv_health[prn - 1], prn == 30 ? 0x3F : 0) << "PRN " << prn;
  EXPECT_EQ(p4->sv_health[0], -1);
}

TEST(LnavMessage, ReservedPagesCarryAlternatingFill) {
  const auto c = content_with(real_ephemeris_prn1());
  for (int page : {1, 12, 13, 14, 17, 19}) {
    const auto words = encode_subframe(4, c, 100, page);
    const auto sf = decode_subframe(words);
    ASSERT_TRUE(sf.has_value()) << page;
    EXPECT_EQ(sf->sv_id, page_sv_id(4, page));
    // Word 4 is all fill: its data bits, polarity restored with D29*/D30* of word 3, alternate.
    const auto data4 = check_word(words[3], word_d29(words[2]), word_d30(words[2]));
    ASSERT_TRUE(data4.has_value());
    EXPECT_TRUE(*data4 == 0xAAAAAAu || *data4 == 0x555555u) << std::hex << *data4;
  }
}

// Splits a bit vector into 30-bit words starting at bit offset.
std::uint32_t word_at(const std::vector<std::uint8_t>& bits, std::size_t offset) {
  std::uint32_t w = 0;
  for (std::size_t i = 0; i < 30; ++i) w = (w << 1) | bits[offset + i];
  return w;
}

Subframe subframe_at(const std::vector<std::uint8_t>& bits, std::size_t offset) {
  Subframe sf{};
  for (std::size_t w = 0; w < 10; ++w) sf[w] = word_at(bits, offset + 30 * w);
  return sf;
}

TEST(LnavMessage, ContinuousBitStreamDecodesAcrossBoundaries) {
  const auto c = content_with_almanac();
  // Start mid-subframe, 7 s before the end of the week, and run across the week rollover.
  const std::int64_t first_bit = kBitsPerWeek - 350 * 50 + 137;
  const int n_bits = 50 * 350;
  const auto bits = lnav_bits(c, first_bit, n_bits);
  ASSERT_EQ(bits.size(), static_cast<std::size_t>(n_bits));

  // Word parity chains across every word and subframe boundary in the stream.
  const std::size_t first_word = static_cast<std::size_t>((30 - first_bit % 30) % 30);
  bool d29 = bits[first_word - 2], d30 = bits[first_word - 1];
  int words_checked = 0;
  for (std::size_t off = first_word; off + 30 <= bits.size(); off += 30, ++words_checked) {
    const auto w = word_at(bits, off);
    ASSERT_TRUE(check_word(w, d29, d30).has_value()) << "word at stream bit " << off;
    d29 = word_d29(w);
    d30 = word_d30(w);
  }
  EXPECT_GT(words_checked, 500);

  const std::size_t first_sf = static_cast<std::size_t>((300 - first_bit % 300) % 300);
  int previous_tow = -1, decoded = 0;
  EphemerisAssembler assembler(1, 2190);
  for (std::size_t off = first_sf; off + 300 <= bits.size(); off += 300, ++decoded) {
    const auto sf = decode_subframe(subframe_at(bits, off));
    ASSERT_TRUE(sf.has_value()) << "subframe at stream bit " << off;
    const std::int64_t k = (first_bit + static_cast<std::int64_t>(off)) / 300 % kTowCountsPerWeek;
    EXPECT_EQ(sf->tlm_how.subframe_id, subframe_id_at(k));
    EXPECT_EQ(sf->tlm_how.tow_count, (k + 1) % kTowCountsPerWeek);
    if (previous_tow >= 0) {
      EXPECT_EQ(sf->tlm_how.tow_count, (previous_tow + 1) % kTowCountsPerWeek);
    }
    previous_tow = sf->tlm_how.tow_count;
    assembler.add(*sf);

    // The same subframe read from the inverted stream decodes to the same content.
    auto inv = subframe_at(bits, off);
    for (auto& w : inv) w = ~w & kWordMask;
    const auto sf_inv = decode_subframe(inv);
    ASSERT_TRUE(sf_inv.has_value());
    EXPECT_TRUE(sf_inv->inverted);
    EXPECT_EQ(sf_inv->tlm_how.tow_count, sf->tlm_how.tow_count);
    EXPECT_EQ(sf_inv->sv_id, sf->sv_id);
    EXPECT_EQ(sf_inv->eph.m0_rad, sf->eph.m0_rad);
    EXPECT_EQ(sf_inv->eph.af0_s, sf->eph.af0_s);
  }
  EXPECT_GE(decoded, 49);
  EXPECT_EQ(previous_tow % kTowCountsPerWeek, static_cast<int>((first_bit + n_bits) / 300 % kTowCountsPerWeek));
  ASSERT_TRUE(assembler.ephemeris().has_value());
  EXPECT_EQ(assembler.ephemeris()->week, 2190);
  EXPECT_NEAR(assembler.ephemeris()->m0_rad, c.eph.m0_rad, 0x1p-32 * kSc);
}

TEST(LnavMessage, BitSourceMatchesWholeSubframes) {
  const auto c = content_with(real_ephemeris_prn1());
  LnavBitSource source(c);
  for (std::int64_t k : {std::int64_t{0}, std::int64_t{7}, std::int64_t{100799}}) {
    const auto sf = subframe_of_week(c, k);
    for (int i = 0; i < kBitsPerSubframe; ++i) ASSERT_EQ(source.bit_at(k * 300 + i), subframe_bit(sf, i));
  }
  // Bit indices wrap into the next week.
  EXPECT_EQ(source.bit_at(kBitsPerWeek + 5), subframe_bit(subframe_of_week(c, 0), 5));
}

TEST(LnavMessage, AssemblerNeedsMatchingIssueOfData) {
  auto c = content_with(real_ephemeris_prn1());
  EphemerisAssembler assembler(1, 2190);
  EXPECT_FALSE(assembler.add(*decode_subframe(encode_subframe(1, c, 1, 1))));
  EXPECT_FALSE(assembler.add(*decode_subframe(encode_subframe(2, c, 2, 1))));
  auto c_new = c;
  c_new.eph.iode = 40;  // subframe 3 from the next upload
  EXPECT_FALSE(assembler.add(*decode_subframe(encode_subframe(3, c_new, 3, 1))));
  EXPECT_FALSE(assembler.ephemeris().has_value());
  // IODC 0x127 has 8 LSBs 0x27 = 39, which matches IODE 39.
  c.eph.iodc = 0x127;
  EXPECT_FALSE(assembler.add(*decode_subframe(encode_subframe(1, c, 6, 1))));
  EXPECT_TRUE(assembler.add(*decode_subframe(encode_subframe(3, c, 8, 1))));
  ASSERT_TRUE(assembler.ephemeris().has_value());
  EXPECT_EQ(assembler.ephemeris()->iodc, 0x127);
  // The same data again is not a new ephemeris.
  EXPECT_FALSE(assembler.add(*decode_subframe(encode_subframe(2, c, 7, 1))));
}

TEST(LnavMessage, SubframeOneCarriesTheWeekOfTransmission) {
  // An ephemeris of toe 2191/0 sent in the last minutes of week 2190: WN is 2190's, and
  // the assembled ephemeris's week is toe's (2191), from WN and the time of transmission.
  auto c = content_with(real_ephemeris_prn1());
  c.eph.week = 2191;
  c.eph.toe_s = 0.0;
  c.eph.toc_s = 0.0;
  c.transmission_week = 2190;
  const auto sf1 = decode_subframe(encode_subframe(1, c, 100797, 1));
  ASSERT_TRUE(sf1.has_value());
  EXPECT_EQ(sf1->eph.week, 2190 % 1024);
  EphemerisAssembler late(1, 2190);
  late.add(*sf1);
  late.add(*decode_subframe(encode_subframe(2, c, 100798, 1)));
  late.add(*decode_subframe(encode_subframe(3, c, 100799, 1)));
  ASSERT_TRUE(late.ephemeris().has_value());
  EXPECT_EQ(late.ephemeris()->week, 2191);
  EXPECT_EQ(late.ephemeris()->transmission_time_s, 604776.0);
  // Toe 2190/597600 (22:00 on the last day) still sent after the boundary, in week 2191.
  c.eph.week = 2190;
  c.eph.toe_s = 597600.0;
  c.eph.toc_s = 597600.0;
  c.transmission_week = 2191;
  EphemerisAssembler after(1, 2190);
  after.add(*decode_subframe(encode_subframe(1, c, 1, 1)));
  after.add(*decode_subframe(encode_subframe(2, c, 2, 1)));
  after.add(*decode_subframe(encode_subframe(3, c, 3, 1)));
  ASSERT_TRUE(after.ephemeris().has_value());
  EXPECT_EQ(after.ephemeris()->week, 2190);
  // Without a week of transmission the message carries toe's week (data of one week).
  c.transmission_week.reset();
  EXPECT_EQ(decode_subframe(encode_subframe(1, c, 1, 1))->eph.week, 2190 % 1024);
}

TEST(LnavMessage, WeekResolution) {
  EXPECT_EQ(resolve_week(2190 % 1024, 2190), 2190);
  EXPECT_EQ(resolve_week(2190 % 1024, 2500), 2190);
  EXPECT_EQ(resolve_week(1023, 2048), 2047);  // just before a rollover
  EXPECT_EQ(resolve_week(0, 2047), 2048);     // just after
  EXPECT_EQ(resolve_week(5, 3), 5);
}

TEST(LnavMessage, CorruptedBitsAreRejected) {
  const auto c = content_with_almanac();
  std::mt19937_64 rng(1234);
  int heavy_accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::int64_t k = static_cast<std::int64_t>(rng() % 125);
    const auto clean = subframe_of_week(c, k);
    auto bad = clean;
    // 1 to 3 flipped bits: every damaged word has at most 3 errors, which the (32,26) code
    // always detects.
    const int flips = 1 + static_cast<int>(rng() % 3);
    std::vector<int> positions;
    while (static_cast<int>(positions.size()) < flips) {
      const int p = static_cast<int>(rng() % 300);
      if (std::find(positions.begin(), positions.end(), p) == positions.end()) positions.push_back(p);
    }
    for (int p : positions) bad[p / 30] ^= 1u << (29 - p % 30);
    ASSERT_FALSE(decode_subframe(bad).has_value()) << "trial " << trial << " flips " << flips;

    // Heavy damage (8 random bits): rarely passes, and never both passes and differs without
    // every damaged word having a valid codeword (checked by re-encoding).
    auto heavy = clean;
    for (int i = 0; i < 8; ++i) {
      const int p = static_cast<int>(rng() % 30) + 30 * static_cast<int>(rng() % 10);
      heavy[p / 30] ^= 1u << (29 - p % 30);
    }
    if (heavy != clean && decode_subframe(heavy).has_value()) ++heavy_accepted;
  }
  EXPECT_LT(heavy_accepted, 30) << "of 3000 heavily corrupted subframes";
}

TEST(LnavMessage, RandomInputNeverCrashesTheDecoder) {
  std::mt19937_64 rng(99);
  int accepted = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Subframe sf{};
    if (trial % 2 == 0) {
      for (auto& w : sf) w = static_cast<std::uint32_t>(rng()) & kWordMask;
    } else {
      // Valid parity everywhere and a preamble, with random content: exercises every field
      // decoder, including subframe IDs 0, 6 and 7 and out-of-range TOW counts.
      bool d29 = false, d30 = false;
      for (int w = 0; w < 10; ++w) {
        std::uint32_t data = static_cast<std::uint32_t>(rng()) & kDataMask;
        if (w == 0) data = (kPreamble << 16) | (data & 0xFFFF);
        sf[w] = encode_word(data, d29, d30);
        d29 = word_d29(sf[w]);
        d30 = word_d30(sf[w]);
      }
      if (trial % 4 == 1) {
        for (auto& w : sf) w = ~w & kWordMask;
      }
    }
    const auto decoded = decode_subframe(sf);
    if (decoded) {
      ++accepted;
      EXPECT_GE(decoded->tlm_how.subframe_id, 1);
      EXPECT_LE(decoded->tlm_how.subframe_id, 5);
      EXPECT_LT(decoded->tlm_how.tow_count, kTowCountsPerWeek);
    }
  }
  EXPECT_GT(accepted, 3000);  // the parity-valid half mostly passes (subframe ID 1..5 is 5/8)
  EXPECT_LT(accepted, 10000);
}

}  // namespace
}  // namespace deepnav::lnav
