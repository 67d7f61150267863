// Independent check of the LNAV bit layout: subframes encoded here are handed to RTKLIB's
// convbin as u-blox RXM-SFRBX messages, and the RINEX navigation file it writes must carry
// the ephemeris, ionosphere and UTC values that went in. Skipped when convbin is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "signals/lnav_message.hpp"
#include "signals/lnav_parity.hpp"

namespace deepnav::lnav {
namespace {

namespace fs = std::filesystem;

bool have_convbin() { return std::system("command -v convbin >/dev/null 2>&1") == 0; }

void put_u32_le(std::vector<std::uint8_t>& v, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) v.push_back(static_cast<std::uint8_t>(x >> (8 * i)));
}

// UBX-RXM-SFRBX carries each GPS word's 24 data bits, polarity restored, in bits 29..6.
std::vector<std::uint8_t> sfrbx_message(int prn, const Subframe& sf) {
  std::vector<std::uint8_t> payload = {0 /*GPS*/, static_cast<std::uint8_t>(prn), 0, 0, 10, 0, 2, 0};
  bool d29 = false, d30 = false;
  for (const auto word : sf) {
    const auto data = check_word(word, d29, d30);
    EXPECT_TRUE(data.has_value());
    put_u32_le(payload, data.value_or(0) << 6);
    d29 = word_d29(word);
    d30 = word_d30(word);
  }
  std::vector<std::uint8_t> msg;
  msg.reserve(payload.size() + 8);
  for (const std::uint8_t byte : {std::uint8_t{0xB5}, std::uint8_t{0x62}, std::uint8_t{0x02}, std::uint8_t{0x13}}) {
    msg.push_back(byte);
  }
  msg.push_back(static_cast<std::uint8_t>(payload.size() & 0xFF));
  msg.push_back(static_cast<std::uint8_t>(payload.size() >> 8));
  for (const auto byte : payload) msg.push_back(byte);
  std::uint8_t ck_a = 0, ck_b = 0;
  for (std::size_t i = 2; i < msg.size(); ++i) {
    ck_a = static_cast<std::uint8_t>(ck_a + msg[i]);
    ck_b = static_cast<std::uint8_t>(ck_b + ck_a);
  }
  msg.push_back(ck_a);
  msg.push_back(ck_b);
  return msg;
}

// Values of a RINEX 3 record: three on the first line after the epoch, four per line after.
std::vector<double> rinex_values(const std::vector<std::string>& lines) {
  std::vector<double> out;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    std::string line = lines[li];
    std::replace(line.begin(), line.end(), 'D', 'E');
    const std::size_t start = li == 0 ? 23 : 4;
    for (std::size_t col = start; col < line.size(); col += 19) {
      out.push_back(std::stod(line.substr(col, 19)));
    }
  }
  return out;
}

Ephemeris reference_ephemeris() {
  Ephemeris e;
  e.prn = 1;
  e.week = 2190;
  e.iodc = 39;
  e.iode = 39;
  e.ura_index = 0;
  e.code_on_l2 = 1;
  e.toc_s = 518400.0;
  e.af0_s = 0.469126738608e-03;
  e.af1_sps = -0.100044417195e-10;
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

TEST(LnavRtklibCrosscheck, ConvbinDecodesOurSubframes) {
  if (!have_convbin()) GTEST_SKIP() << "RTKLIB convbin not installed";
  LnavContent c;
  c.eph = reference_ephemeris();
  // Distinct counts in every field, so that swapped fields cannot agree by accident.
  c.iono.alpha = {13 * 0x1p-30, -3 * 0x1p-27, -2 * 0x1p-24, 10 * 0x1p-24};
  c.iono.beta = {57 * 0x1p11, -15 * 0x1p14, -1 * 0x1p16, 17 * 0x1p16};
  c.utc.a0_s = 0.279396772385e-08;
  c.utc.a1_sps = 0.799360577730e-14;
  c.utc.tot_s = 147456;
  c.utc.wnt = 2191 & 0xFF;
  c.utc.delta_t_ls = 18;
  c.utc.wn_lsf = 2185 & 0xFF;
  c.utc.dn = 7;
  c.utc.delta_t_lsf = 18;

  const fs::path dir = fs::path(DEEPNAV_BINARY_DIR) / "lnav_rtklib_crosscheck";
  fs::create_directories(dir);
  const fs::path ubx = dir / "nav.ubx", nav = dir / "nav.rnx";
  fs::remove(nav);
  {
    std::ofstream out(ubx, std::ios::binary);
    // One full page cycle from two subframes before toe, so that page 18 is included.
    const std::int64_t k0 = static_cast<std::int64_t>(c.eph.toe_s) / 6 - 2;
    for (std::int64_t k = k0; k < k0 + 130; ++k) {
      const auto msg = sfrbx_message(1, subframe_of_week(c, k));
      out.write(reinterpret_cast<const char*>(msg.data()), static_cast<std::streamsize>(msg.size()));
    }
  }
  const std::string cmd = "convbin -r ubx -v 3.03 -oi -ot -ol -n '" + nav.string() + "' -o '" +
                          (dir / "nav.obs").string() + "' '" + ubx.string() + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  std::ifstream in(nav);
  ASSERT_TRUE(in) << "convbin wrote no " << nav;
  std::vector<std::string> header, record;
  std::string line;
  bool in_header = true;
  while (std::getline(in, line)) {
    if (in_header) {
      header.push_back(line);
      if (line.find("END OF HEADER") != std::string::npos) in_header = false;
    } else if (line.rfind("G01", 0) == 0 || (!record.empty() && record.size() < 8)) {
      record.push_back(line);
    }
  }
  ASSERT_EQ(record.size(), 8u) << "no GPS PRN 1 record in " << nav;
  const auto v = rinex_values(record);
  ASSERT_GE(v.size(), 27u);
  const auto& e = c.eph;
  // RINEX 3 GPS record order: af0 af1 af2 | IODE Crs dn M0 | Cuc e Cus sqrtA | toe Cic OMEGA0 Cis
  // | i0 Crc omega OMEGADOT | IDOT L2codes week L2P | URA health TGD IODC | ttr fit.
  const std::vector<std::pair<double, double>> pairs = {
      {v[0], e.af0_s},       {v[1], e.af1_sps},       {v[2], e.af2_sps2},         {v[3], e.iode},
      {v[4], e.crs_m},       {v[5], e.delta_n_radps}, {v[6], e.m0_rad},           {v[7], e.cuc_rad},
      {v[8], e.e},           {v[9], e.cus_rad},       {v[10], e.sqrt_a},          {v[11], e.toe_s},
      {v[12], e.cic_rad},    {v[13], e.omega0_rad},   {v[14], e.cis_rad},         {v[15], e.i0_rad},
      {v[16], e.crc_m},      {v[17], e.omega_rad},    {v[18], e.omega_dot_radps}, {v[19], e.idot_radps},
      {v[20], e.code_on_l2}, {v[21], e.week},         {v[24], e.health},          {v[25], e.tgd_s},
      {v[26], e.iodc},
  };
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto [got, want] = pairs[i];
    EXPECT_NEAR(got, want, 1e-11 * std::max(1.0, std::abs(want))) << "value " << i;
  }

  std::string iono_a, iono_b, utc, leap;
  for (const auto& h : header) {
    if (h.rfind("GPSA", 0) == 0) iono_a = h;
    if (h.rfind("GPSB", 0) == 0) iono_b = h;
    if (h.rfind("GPUT", 0) == 0) utc = h;
    if (h.find("LEAP SECONDS") != std::string::npos) leap = h;
  }
  ASSERT_FALSE(iono_a.empty() || iono_b.empty() || utc.empty() || leap.empty());
  auto fields = [](std::string s, std::size_t from, int n, std::size_t width) {
    std::replace(s.begin(), s.end(), 'D', 'E');
    std::vector<double> out;
    for (int i = 0; i < n; ++i) out.push_back(std::stod(s.substr(from + i * width, width)));
    return out;
  };
  const auto a = fields(iono_a, 5, 4, 12), b = fields(iono_b, 5, 4, 12);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(a[i], c.iono.alpha[i], 1e-3 * std::abs(c.iono.alpha[i])) << "alpha" << i;
    EXPECT_NEAR(b[i], c.iono.beta[i], 1e-3 * std::abs(c.iono.beta[i])) << "beta" << i;
  }
  std::istringstream utc_in(utc.substr(4, 56));
  std::string a0_text, a1_text;
  int tot = 0;
  utc_in >> a0_text >> a1_text >> tot;
  std::replace(a0_text.begin(), a0_text.end(), 'D', 'E');
  std::replace(a1_text.begin(), a1_text.end(), 'D', 'E');
  EXPECT_NEAR(std::stod(a0_text), c.utc.a0_s, 1e-18);
  EXPECT_NEAR(std::stod(a1_text), c.utc.a1_sps, 1e-23);
  EXPECT_EQ(tot, c.utc.tot_s);
  std::istringstream leap_in(leap);
  int dt_ls = 0, dt_lsf = 0;
  leap_in >> dt_ls >> dt_lsf;
  EXPECT_EQ(dt_ls, 18);
  EXPECT_EQ(dt_lsf, 18);
}

}  // namespace
}  // namespace deepnav::lnav
