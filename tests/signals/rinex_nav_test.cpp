#include "signals/rinex_nav.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepnav {
namespace {

const std::string kBrdcPath = std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n";

std::string file_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

NavData read_text(const std::string& text, const std::string& name = "test.nav") {
  std::istringstream in(text);
  return read_rinex_nav(in, name);
}

/// Message of the error reading `text` throws ("" when it does not throw).
std::string error_of(const std::string& text, const std::string& name = "test.nav") {
  try {
    read_text(text, name);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::string brdc_head(std::size_t n_lines) {
  const auto lines = split_lines(file_text(kBrdcPath));
  return join_lines(std::vector<std::string>(lines.begin(), lines.begin() + static_cast<long>(n_lines)));
}

const NavData& brdc() {
  static const NavData nav = read_rinex_nav(kBrdcPath);
  return nav;
}

TEST(RinexNav, ReadsRinex2HeaderOfRealFile) {
  const NavData& nav = brdc();
  EXPECT_DOUBLE_EQ(nav.rinex_version, 2.0);
  ASSERT_TRUE(nav.iono.valid);
  EXPECT_DOUBLE_EQ(nav.iono.alpha[0], 0.1211e-07);
  EXPECT_DOUBLE_EQ(nav.iono.alpha[1], -0.7451e-08);
  EXPECT_DOUBLE_EQ(nav.iono.alpha[2], -0.5960e-07);
  EXPECT_DOUBLE_EQ(nav.iono.alpha[3], 0.1192e-06);
  EXPECT_DOUBLE_EQ(nav.iono.beta[0], 0.1167e+06);
  EXPECT_DOUBLE_EQ(nav.iono.beta[1], -0.2458e+06);
  EXPECT_DOUBLE_EQ(nav.iono.beta[2], -0.6554e+05);
  EXPECT_DOUBLE_EQ(nav.iono.beta[3], 0.1114e+07);
  ASSERT_TRUE(nav.utc.valid);
  EXPECT_DOUBLE_EQ(nav.utc.a0_s, 0.279396772385e-08);
  EXPECT_DOUBLE_EQ(nav.utc.a1_sps, 0.799360577730e-14);
  EXPECT_EQ(nav.utc.tot_s, 147456);
  EXPECT_EQ(nav.utc.wnt, 2191);
  EXPECT_TRUE(nav.leap_seconds_valid);
  EXPECT_EQ(nav.utc.delta_t_ls, 18);
}

TEST(RinexNav, ReadsAllRecordsOfRealFile) {
  // 3384 lines = 8 header lines + 422 records of 8 lines.
  EXPECT_EQ(brdc().ephemerides.size(), 422u);
  EXPECT_EQ(brdc().skipped_records, 0);
}

TEST(RinexNav, FirstRecordMatchesFileText) {
  const Ephemeris& e = brdc().ephemerides.front();
  EXPECT_EQ(e.prn, 1);
  EXPECT_EQ(e.week, 2190);
  EXPECT_DOUBLE_EQ(e.toc_s, 518400.0);  // 2022-01-01 00:00:00 is Saturday of week 2190
  EXPECT_DOUBLE_EQ(e.af0_s, 0.469126738608e-03);
  EXPECT_DOUBLE_EQ(e.af1_sps, -0.100044417195e-10);
  EXPECT_DOUBLE_EQ(e.af2_sps2, 0.0);
  EXPECT_EQ(e.iode, 39);
  EXPECT_DOUBLE_EQ(e.crs_m, -141.125);
  EXPECT_DOUBLE_EQ(e.delta_n_radps, 0.398838041777e-08);
  EXPECT_DOUBLE_EQ(e.m0_rad, -0.624294238235);
  EXPECT_DOUBLE_EQ(e.cuc_rad, -0.736303627491e-05);
  EXPECT_DOUBLE_EQ(e.e, 0.112181392033e-01);
  EXPECT_DOUBLE_EQ(e.cus_rad, 0.469572842121e-05);
  EXPECT_DOUBLE_EQ(e.sqrt_a, 0.515367499542e+04);
  EXPECT_DOUBLE_EQ(e.toe_s, 518400.0);
  EXPECT_DOUBLE_EQ(e.cic_rad, -0.316649675369e-07);
  EXPECT_DOUBLE_EQ(e.omega0_rad, -0.103661124009e+01);
  EXPECT_DOUBLE_EQ(e.cis_rad, 0.195577740669e-06);
  EXPECT_DOUBLE_EQ(e.i0_rad, 0.986418769490);
  EXPECT_DOUBLE_EQ(e.crc_m, 299.75);
  EXPECT_DOUBLE_EQ(e.omega_rad, 0.884087601569);
  EXPECT_DOUBLE_EQ(e.omega_dot_radps, -0.813355308085e-08);
  EXPECT_DOUBLE_EQ(e.idot_radps, -0.377872882780e-09);
  EXPECT_EQ(e.code_on_l2, 1);
  EXPECT_EQ(e.l2p_data_flag, 0);
  EXPECT_EQ(e.ura_index, 0);  // 2.0 m
  EXPECT_EQ(e.health, 0);
  EXPECT_DOUBLE_EQ(e.tgd_s, 0.512227416039e-08);
  EXPECT_EQ(e.iodc, 39);
  EXPECT_TRUE(e.transmission_time_known);
  EXPECT_DOUBLE_EQ(e.transmission_time_s, 511218.0);
  EXPECT_EQ(e.fit_interval_flag, 0);
}

TEST(RinexNav, KnownQuirksOfRealFile) {
  const NavData& nav = brdc();
  bool saw28 = false, saw14 = false;
  for (const Ephemeris& e : nav.ephemerides) {
    if (e.prn == 28) {
      saw28 = true;
      EXPECT_EQ(e.health, 63);
    }
    if (e.prn == 14 && e.toe_s == 518400.0) {
      saw14 = true;
      EXPECT_EQ(e.iodc, 535);
      EXPECT_EQ(e.iode, 23);
      EXPECT_EQ(e.iodc & 0xFF, e.iode);
    }
  }
  EXPECT_TRUE(saw28);
  EXPECT_TRUE(saw14);
  // Last record: toc 23:59:44, toe 604784 s, at the very end of week 2190.
  const Ephemeris& last = nav.ephemerides.back();
  EXPECT_EQ(last.prn, 32);
  EXPECT_DOUBLE_EQ(last.toc_s, 604784.0);
  EXPECT_EQ(last.week, 2190);
}

TEST(RinexNav, SelectPicksClosestHealthyValidEphemeris) {
  const NavData& nav = brdc();
  const GpsTime t0{2190, 518400.0};
  // Unhealthy satellite: never selected.
  EXPECT_EQ(nav.select(28, t0.plus_seconds(1800)), nullptr);
  // 00:50: the 00:00 data set (toe 518400) is closer than the 02:00 one.
  const Ephemeris* e = nav.select(1, t0.plus_seconds(3000));
  ASSERT_NE(e, nullptr);
  EXPECT_DOUBLE_EQ(e->toe_s, 518400.0);
  // 01:10: the 02:00 data set is closer but was transmitted from about 00:00 on, so it is usable.
  e = nav.select(1, t0.plus_seconds(4200));
  ASSERT_NE(e, nullptr);
  EXPECT_DOUBLE_EQ(e->toe_s, 518400.0 + 7200.0);
  // Next week's first second still uses the end-of-week data set of PRN 32 (fit interval spans it).
  e = nav.select(32, GpsTime{2191, 10.0});
  ASSERT_NE(e, nullptr);
  EXPECT_DOUBLE_EQ(e->toe_s, 604784.0);
  EXPECT_EQ(e->week, 2190);
  // A day later nothing is within its fit interval.
  EXPECT_EQ(nav.select(1, GpsTime{2191, 86400.0 + 3 * 3600.0}), nullptr);
  // PRN with no data at all.
  EXPECT_EQ(nav.select(33, t0), nullptr);
}

TEST(RinexNav, SelectPrefersDataAlreadyTransmitted) {
  NavData nav;
  Ephemeris early;
  early.prn = 5;
  early.week = 2190;
  early.toe_s = 518400.0;
  early.transmission_time_s = 511200.0;
  early.transmission_time_known = true;
  Ephemeris late = early;
  late.toe_s = 518400.0 + 7200.0;
  late.transmission_time_s = late.toe_s - 600.0;  // cut in late, at 01:50
  nav.ephemerides = {early, late};
  // At 01:20 the later set is closer in toe but not yet transmitted.
  const GpsTime t_0120{2190, 518400.0 + 4800.0};
  EXPECT_DOUBLE_EQ(nav.select(5, t_0120)->toe_s, 518400.0);
  // With its transmission time unknown, the closer toe wins.
  nav.ephemerides[1].transmission_time_known = false;
  EXPECT_DOUBLE_EQ(nav.select(5, t_0120)->toe_s, 518400.0 + 7200.0);
  // After 01:50 it is the better one.
  nav.ephemerides[1].transmission_time_known = true;
  EXPECT_DOUBLE_EQ(nav.select(5, t_0120.plus_seconds(1800.0 + 1.0))->toe_s, 518400.0 + 7200.0);
  // When only the future one is valid, it is still returned.
  // At 02:10 the early set is past its fit interval; the late one is returned even though
  // its (here, 02:30) transmission time is still ahead.
  nav.ephemerides[1].transmission_time_s = late.toe_s + 1800.0;
  EXPECT_DOUBLE_EQ(nav.select(5, GpsTime{2190, 518400.0 + 7800.0})->toe_s, 518400.0 + 7200.0);
}

TEST(RinexNav, Rinex3WriterRoundTripIsExact) {
  const NavData& nav = brdc();
  std::ostringstream out;
  write_rinex3_nav(out, nav, "deepnav");
  const NavData back = read_text(out.str(), "roundtrip.rnx");
  EXPECT_DOUBLE_EQ(back.rinex_version, 3.04);
  ASSERT_EQ(back.ephemerides.size(), nav.ephemerides.size());
  for (std::size_t i = 0; i < nav.ephemerides.size(); ++i) {
    const Ephemeris& a = nav.ephemerides[i];
    const Ephemeris& b = back.ephemerides[i];
    SCOPED_TRACE("record " + std::to_string(i) + " PRN " + std::to_string(a.prn));
    // 13 significant digits hold the 12 of RINEX 2 exactly: equal doubles.
    EXPECT_EQ(a.prn, b.prn);
    EXPECT_EQ(a.week, b.week);
    EXPECT_EQ(a.iodc, b.iodc);
    EXPECT_EQ(a.iode, b.iode);
    EXPECT_EQ(a.health, b.health);
    EXPECT_EQ(a.ura_index, b.ura_index);
    EXPECT_EQ(a.code_on_l2, b.code_on_l2);
    EXPECT_EQ(a.l2p_data_flag, b.l2p_data_flag);
    EXPECT_EQ(a.fit_interval_flag, b.fit_interval_flag);
    EXPECT_EQ(a.toc_s, b.toc_s);
    EXPECT_EQ(a.af0_s, b.af0_s);
    EXPECT_EQ(a.af1_sps, b.af1_sps);
    EXPECT_EQ(a.af2_sps2, b.af2_sps2);
    EXPECT_EQ(a.tgd_s, b.tgd_s);
    EXPECT_EQ(a.toe_s, b.toe_s);
    EXPECT_EQ(a.sqrt_a, b.sqrt_a);
    EXPECT_EQ(a.e, b.e);
    EXPECT_EQ(a.m0_rad, b.m0_rad);
    EXPECT_EQ(a.delta_n_radps, b.delta_n_radps);
    EXPECT_EQ(a.omega0_rad, b.omega0_rad);
    EXPECT_EQ(a.omega_dot_radps, b.omega_dot_radps);
    EXPECT_EQ(a.i0_rad, b.i0_rad);
    EXPECT_EQ(a.idot_radps, b.idot_radps);
    EXPECT_EQ(a.omega_rad, b.omega_rad);
    EXPECT_EQ(a.cuc_rad, b.cuc_rad);
    EXPECT_EQ(a.cus_rad, b.cus_rad);
    EXPECT_EQ(a.crc_m, b.crc_m);
    EXPECT_EQ(a.crs_m, b.crs_m);
    EXPECT_EQ(a.cic_rad, b.cic_rad);
    EXPECT_EQ(a.cis_rad, b.cis_rad);
    EXPECT_EQ(a.transmission_time_known, b.transmission_time_known);
    EXPECT_EQ(a.transmission_time_s, b.transmission_time_s);
  }
  EXPECT_EQ(back.iono.alpha, nav.iono.alpha);
  EXPECT_EQ(back.iono.beta, nav.iono.beta);
  EXPECT_TRUE(back.iono.valid);
  ASSERT_TRUE(back.utc.valid);
  // RINEX 3 holds A0 with 11 and A1 with 10 significant digits (D17.10, D16.9).
  EXPECT_NEAR(back.utc.a0_s, nav.utc.a0_s, 1e-19);
  EXPECT_NEAR(back.utc.a1_sps, nav.utc.a1_sps, 1e-24);
  EXPECT_EQ(back.utc.tot_s, nav.utc.tot_s);
  EXPECT_EQ(back.utc.wnt, nav.utc.wnt);
  EXPECT_EQ(back.utc.delta_t_ls, 18);

  // Writing what was read back gives the same bytes (deterministic, lossless second pass).
  std::ostringstream again;
  write_rinex3_nav(again, back, "deepnav");
  EXPECT_EQ(again.str(), out.str());
}

TEST(RinexNav, Rinex3WriterFollowsColumnLayout) {
  NavData nav;
  nav.ephemerides = {brdc().ephemerides.front()};
  nav.leap_seconds_valid = true;
  nav.utc.delta_t_ls = 18;
  std::ostringstream out;
  write_rinex3_nav(out, nav, "deepnav");
  const auto lines = split_lines(out.str());
  ASSERT_GE(lines.size(), 8u);
  EXPECT_EQ(lines[0], "     3.04           N: GNSS NAV DATA    G: GPS              RINEX VERSION / TYPE");
  EXPECT_EQ(lines[1].substr(40, 19), "20220101 000000 GPS");
  EXPECT_EQ(lines[2], "    18                                                      LEAP SECONDS        ");
  EXPECT_EQ(lines[3].substr(60), "END OF HEADER       ");
  EXPECT_EQ(lines[4], "G01 2022 01 01 00 00 00 4.691267386080E-04-1.000444171950E-11 0.000000000000E+00");
  EXPECT_EQ(lines[5], "     3.900000000000E+01-1.411250000000E+02 3.988380417770E-09-6.242942382350E-01");
  EXPECT_EQ(lines[11], "     5.112180000000E+05 4.000000000000E+00");
}

/// A RINEX 3.04 mixed file with GLONASS (4 lines), Galileo (8), SBAS (4) records around GPS ones.
std::string mixed_rinex3() {
  std::ostringstream gps;
  NavData two;
  two.ephemerides = {brdc().ephemerides[0], brdc().ephemerides[1]};
  write_rinex3_nav(gps, two, "deepnav");
  auto lines = split_lines(gps.str());
  lines[0] = "     3.04           N: GNSS NAV DATA    M: Mixed            RINEX VERSION / TYPE";
  const std::vector<std::string> glonass = {
      "R01 2022 01 01 00 15 00 7.767230272293E-06 0.000000000000E+00 5.400000000000E+04",
      "     1.155651904297E+04-1.627574920654E+00 1.862645149231E-09 0.000000000000E+00",
      "    -1.205268261719E+04-2.130239486694E+00 9.313225746155E-10 1.000000000000E+00",
      "     1.877624169922E+04 4.074697494507E-01-2.793967723846E-09 0.000000000000E+00"};
  const std::vector<std::string> galileo = {
      "E11 2022 01 01 00 10 00-6.422358565032E-04-8.128608897095E-12 0.000000000000E+00",
      "     2.000000000000E+00-1.371875000000E+02 2.661539716634E-09 2.138893520483E+00",
      "    -6.387382745743E-06 1.963521935977E-04 1.047365367413E-05 5.440621742249E+03",
      "     5.190000000000E+05-1.862645149231E-09 2.104007085693E+00-4.470348358154E-08",
      "     9.773000390587E-01 1.339687500000E+02 2.968466032393E-01-5.351294601000E-09",
      "     2.175090605839E-10 5.170000000000E+02 2.190000000000E+03 0.000000000000E+00",
      "     3.120000000000E+00 0.000000000000E+00-5.820766091347E-09-6.286427378654E-09",
      "     5.197550000000E+05"};
  const std::vector<std::string> sbas = {
      "S27 2022 01 01 00 01 04 0.000000000000E+00 0.000000000000E+00 5.184640000000E+05",
      "     3.546856000000E+04 0.000000000000E+00 0.000000000000E+00 6.300000000000E+01",
      "    -1.616752000000E+04 0.000000000000E+00 0.000000000000E+00 4.096000000000E+03",
      "     1.017280000000E+03 0.000000000000E+00 0.000000000000E+00 1.120000000000E+02"};
  std::vector<std::string> out;
  std::size_t header_end = 0;
  while (lines[header_end].find("END OF HEADER") == std::string::npos) ++header_end;
  out.insert(out.end(), lines.begin(), lines.begin() + static_cast<long>(header_end) + 1);
  out.insert(out.end(), glonass.begin(), glonass.end());
  out.insert(out.end(), lines.begin() + static_cast<long>(header_end) + 1,
             lines.begin() + static_cast<long>(header_end) + 9);
  out.insert(out.end(), galileo.begin(), galileo.end());
  out.insert(out.end(), sbas.begin(), sbas.end());
  out.insert(out.end(), lines.begin() + static_cast<long>(header_end) + 9, lines.end());
  out.insert(out.end(), glonass.begin(), glonass.end());
  return join_lines(out);
}

TEST(RinexNav, MixedRinex3ReadsGpsAndGalileoAndSkipsOtherSystems) {
  const NavData nav = read_text(mixed_rinex3(), "mixed.rnx");
  ASSERT_EQ(nav.ephemerides.size(), 2u);
  EXPECT_EQ(nav.skipped_records, 3);  // two GLONASS records and an SBAS one
  ASSERT_EQ(nav.galileo_ephemerides.size(), 1u);
  EXPECT_EQ(nav.galileo_ephemerides[0].prn, 11);
  EXPECT_EQ(nav.galileo_ephemerides[0].week, 2190 - 1024);
  EXPECT_EQ(nav.ephemerides[0].prn, 1);
  EXPECT_EQ(nav.ephemerides[1].prn, 2);
  EXPECT_EQ(nav.ephemerides[1].sqrt_a, brdc().ephemerides[1].sqrt_a);
}

TEST(RinexNav, WeekWrittenModulo1024IsRepairedFromTheEpochLine) {
  auto lines = split_lines(brdc_head(16));
  lines[13].replace(41, 19, " 0.142000000000D+03");  // 2190 - 2 * 1024
  const NavData nav = read_text(join_lines(lines));
  ASSERT_EQ(nav.ephemerides.size(), 1u);
  EXPECT_EQ(nav.ephemerides[0].week, 2190);
}

TEST(RinexNavErrors, TruncatedGpsRecordInMixedFile) {
  auto lines = split_lines(mixed_rinex3());
  std::size_t g02 = 0;
  while (lines[g02].rfind("G02", 0) != 0) ++g02;
  lines.erase(lines.begin() + static_cast<long>(g02) + 3, lines.begin() + static_cast<long>(g02) + 8);
  const std::string msg = error_of(join_lines(lines), "mixed.rnx");
  const std::string expected = "mixed.rnx:" + std::to_string(g02 + 4) + ": record of PRN 2 (line " +
                               std::to_string(g02 + 1) + ") is truncated: expected broadcast orbit line 3";
  EXPECT_NE(msg.find(expected), std::string::npos) << msg;
}

TEST(RinexNav, Rinex3HeaderFields) {
  const std::string text =
      "     3.04           N: GNSS NAV DATA    M: Mixed            RINEX VERSION / TYPE\n"
      "GPSA   1.2107E-08 -7.4506E-09 -5.9605E-08  1.1921E-07       IONOSPHERIC CORR\n"
      "GPSB   1.1674E+05 -2.4576E+05 -6.5536E+04  1.1141E+06       IONOSPHERIC CORR\n"
      "GAL    2.9500E+01  2.3438E-01  3.3569E-03  0.0000E+00       IONOSPHERIC CORR\n"
      "GPUT -2.7939677238E-09-7.993605778E-15 147456 2191          TIME SYSTEM CORR\n"
      "GAUT  9.3132257462E-10 0.000000000E+00 432000 2190          TIME SYSTEM CORR\n"
      "    18    18  2185     7                                    LEAP SECONDS\n"
      "                                                            END OF HEADER\n";
  const NavData nav = read_text(text);
  EXPECT_TRUE(nav.iono.valid);
  EXPECT_DOUBLE_EQ(nav.iono.alpha[0], 1.2107e-08);
  EXPECT_DOUBLE_EQ(nav.iono.beta[3], 1.1141e+06);
  EXPECT_TRUE(nav.utc.valid);
  EXPECT_DOUBLE_EQ(nav.utc.a0_s, -2.7939677238e-09);
  EXPECT_DOUBLE_EQ(nav.utc.a1_sps, -7.993605778e-15);
  EXPECT_EQ(nav.utc.tot_s, 147456);
  EXPECT_EQ(nav.utc.wnt, 2191);
  EXPECT_EQ(nav.utc.delta_t_ls, 18);
  EXPECT_EQ(nav.utc.delta_t_lsf, 18);
  EXPECT_EQ(nav.utc.wn_lsf, 2185);
  EXPECT_EQ(nav.utc.dn, 7);
  EXPECT_TRUE(nav.ephemerides.empty());
}

// ---------------------------------------------------------------------------
// Bad input

TEST(RinexNavErrors, MissingAndEmptyFile) {
  try {
    read_rinex_nav("/nonexistent/brdc9999.22n");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("brdc9999.22n: cannot open"), std::string::npos) << e.what();
  }
  // A name past the system's limit: the same error, not std::filesystem::filesystem_error.
  const std::string too_long(5000, 'x');
  try {
    read_rinex_nav(too_long);
    FAIL() << "no error";
  } catch (const std::filesystem::filesystem_error& e) {
    FAIL() << "filesystem_error escaped: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(": cannot open RINEX navigation file"), std::string::npos) << e.what();
  }
  EXPECT_NE(error_of("", "empty.22n").find("empty.22n:0: empty file"), std::string::npos) << error_of("");
}

TEST(RinexNavErrors, WrongFileTypeAndVersion) {
  const std::string obs = "     2.11           OBSERVATION DATA    G (GPS)             RINEX VERSION / TYPE\n";
  EXPECT_NE(error_of(obs).find("test.nav:1: not a GPS navigation file: file type 'O'"), std::string::npos)
      << error_of(obs);
  const std::string v4 = "     4.00           N: GNSS NAV DATA    M: MIXED            RINEX VERSION / TYPE\n";
  EXPECT_NE(error_of(v4).find("test.nav:1: unsupported RINEX version 4.00"), std::string::npos) << error_of(v4);
  const std::string text = "hello world\nthis is not rinex\n";
  EXPECT_NE(error_of(text).find("test.nav:1: not a RINEX file"), std::string::npos) << error_of(text);
}

TEST(RinexNavErrors, MissingEndOfHeader) {
  auto lines = split_lines(brdc_head(24));
  lines.erase(lines.begin() + 7);  // END OF HEADER
  const std::string msg = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg.find("brdc0010.22n:8: expected END OF HEADER"), std::string::npos) << msg;
  // Header only, without END OF HEADER.
  const std::string msg2 = error_of(brdc_head(7), "brdc0010.22n");
  EXPECT_NE(msg2.find("brdc0010.22n:7: no END OF HEADER"), std::string::npos) << msg2;
}

TEST(RinexNavErrors, TruncatedRecord) {
  // Two records, the second cut after its 4th broadcast orbit line.
  const std::string msg = error_of(brdc_head(8 + 8 + 5), "brdc0010.22n");
  EXPECT_NE(msg.find("brdc0010.22n:17: record of PRN 2 is truncated"), std::string::npos) << msg;
  // A record that lost lines in the middle of the file: the next record starts too early.
  auto lines = split_lines(brdc_head(8 + 16));
  lines.erase(lines.begin() + 12, lines.begin() + 16);
  const std::string msg2 = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg2.find("brdc0010.22n:13: record of PRN 1 (line 9) is truncated: expected broadcast orbit line 4"),
            std::string::npos)
      << msg2;
}

TEST(RinexNavErrors, NonNumericAndMissingFields) {
  auto lines = split_lines(brdc_head(16));
  lines[11].replace(25, 5, "12x45");  // broadcast orbit line 3, field 2
  const std::string msg = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg.find("brdc0010.22n:12: broadcast orbit line 3, field 2: expected a number"), std::string::npos) << msg;

  lines = split_lines(brdc_head(16));
  lines[13] = lines[13].substr(0, 60);  // line 5 loses its L2 P flag
  const std::string msg2 = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg2.find("brdc0010.22n:14: expected 4 numbers in broadcast orbit line 5, got '"), std::string::npos)
      << msg2;

  lines = split_lines(brdc_head(16));
  lines[8].replace(0, 2, "4x");
  const std::string msg3 = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg3.find("brdc0010.22n:9: epoch line, PRN (columns 1-2): expected a number"), std::string::npos) << msg3;

  lines = split_lines(brdc_head(16));
  lines[8].replace(6, 2, "13");  // month 13
  const std::string msg4 = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg4.find("brdc0010.22n:9: epoch line, month"), std::string::npos) << msg4;

  lines = split_lines(brdc_head(16));
  lines[3].replace(4, 10, "0.12ab-07 ");
  const std::string msg5 = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg5.find("brdc0010.22n:4: ION ALPHA: expected a number"), std::string::npos) << msg5;

  lines = split_lines(brdc_head(16));
  lines[10].replace(22, 19, " 0.112181392033D+01");  // eccentricity 1.12
  const std::string msg6 = error_of(join_lines(lines), "brdc0010.22n");
  EXPECT_NE(msg6.find("record of PRN 1 starting at line 9: eccentricity"), std::string::npos) << msg6;
}

TEST(RinexNavErrors, AcceptsCrLfAndTrailingBlankLines) {
  std::string text;
  for (const auto& l : split_lines(brdc_head(24))) text += l + "\r\n";
  text += "\r\n\n";
  EXPECT_EQ(read_text(text).ephemerides.size(), 2u);
}

TEST(RinexNavErrors, RandomMutationsNeverCrash) {
  // Random byte changes, deletions, insertions and truncations of the real file (its first
  // 40 records) and of a RINEX 3 version of it: every outcome is either data or an error
  // that names the file and a line.
  const std::string v2 = brdc_head(8 + 40 * 8);
  std::ostringstream v3;
  write_rinex3_nav(v3, read_text(v2), "deepnav");
  const std::string sources[] = {v2, v3.str(), mixed_rinex3()};
  const char alphabet[] = " 0123456789.-+DEeGRSx\n\r\t\0\xff";
  int errors = 0, parsed = 0;
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    std::mt19937_64 rng(seed);
    std::string text = sources[seed % 3];
    const int edits = 1 + static_cast<int>(rng() % 6);
    for (int k = 0; k < edits; ++k) {
      const std::size_t pos = rng() % text.size();
      const char ch = alphabet[rng() % (sizeof(alphabet) - 1)];
      switch (rng() % 4) {
        case 0:
          text[pos] = ch;
          break;
        case 1:
          text.erase(pos, 1 + rng() % 30);
          break;
        case 2:
          text.insert(pos, 1, ch);
          break;
        default:
          text.resize(pos);
          break;
      }
      if (text.empty()) text = "x";
    }
    try {
      const NavData nav = read_text(text, "mutated.nav");
      for (const Ephemeris& e : nav.ephemerides) {
        ASSERT_GE(e.prn, 1);
        ASSERT_LE(e.prn, 32);
        ASSERT_TRUE(e.e >= 0.0 && e.e < 1.0);
      }
      ++parsed;
    } catch (const std::runtime_error& e) {
      ASSERT_EQ(std::string(e.what()).rfind("mutated.nav:", 0), 0u) << e.what();
      ++errors;
    }
  }
  EXPECT_GT(errors, 200);
  EXPECT_GT(parsed, 30);
}

std::string repro(const std::string& name) { return std::string(DEEPNAV_SOURCE_DIR) + "/tests/data/repro/" + name; }

std::string file_error(const std::string& path) {
  try {
    read_rinex_nav(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(RinexNavErrors, FieldsNoSatelliteCanBroadcastNameLineSatelliteAndField) {
  // Finite but absurd values (the reproducers: one field each) used to pass, to hang the
  // synthesizer (range rates of 1e19) or to fail later with a message naming no file.
  struct Case {
    const char* file;
    const char* fragment;
  };
  for (const Case& c : std::vector<Case>{
           {"nav_prn2_deltan_1.23e19.22n",
            "nav_prn2_deltan_1.23e19.22n:10: PRN 2 (record at line 9), broadcast orbit "
            "line 1, field 3: delta n = 1.23457e+19 rad/s is outside [-1.1"},
           {"nav_prn5_cuc_1e29.22n",
            "nav_prn5_cuc_1e29.22n:11: PRN 5 (record at line 9), broadcast orbit line 2, "
            "field 1: Cuc = 1e+29 rad is outside"},
           {"nav_af0_1e300.22n",
            "nav_af0_1e300.22n:9: PRN 1 (record at line 9), epoch line, clock field 1: af0 = "
            "1e+300 s is outside [-0.00097656"},
           {"nav_ion_alpha_1e301.22n", "nav_ion_alpha_1e301.22n:4: ION ALPHA: alpha0 = 1e+300 is outside"},
           {"nav_epoch_feb31.22n",
            "nav_epoch_feb31.22n:9: epoch line, day (columns 9-11): 2022-02-31 is not a date "
            "(2022-02 has 28 days)"}}) {
    const std::string e = file_error(repro(c.file));
    EXPECT_NE(e.find(c.fragment), std::string::npos) << c.file << ": " << e;
  }
  // The real file's values all lie inside (every LNAV field's range).
  EXPECT_EQ(file_error(kBrdcPath), "");
}

TEST(RinexNavErrors, EveryBroadcastFieldIsChecked) {
  // Replace one orbit field of the first record at a time by 1e10 (far beyond any field's
  // range): each is rejected, naming its line and field.
  const auto lines = split_lines(brdc_head(16));
  int rejected = 0;
  for (int orbit_line = 1; orbit_line <= 6; ++orbit_line) {
    for (int field = 0; field < 4; ++field) {
      auto edited = lines;
      std::string& l = edited[static_cast<std::size_t>(8 + orbit_line)];
      l.replace(static_cast<std::size_t>(3 + 19 * field), 19, " 0.100000000000D+11");
      const std::string e = error_of(join_lines(edited));
      if (e.find(fmt::format("broadcast orbit line {}, field {}:", orbit_line, field + 1)) != std::string::npos)
        ++rejected;
    }
  }
  // Lines 1-4 but IODE, e and toe (their own checks come first), and IDOT and TGD of lines
  // 5 and 6; the other fields there are integers with their own checks, and URA.
  EXPECT_EQ(rejected, 15);
}

}  // namespace
}  // namespace deepnav
