// Galileo records and header lines of RINEX 3 navigation files, on the real broadcast data of
// data/galileo_20220220.rnx (see data/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "signals/galileo/galileo_constants.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {

const std::string kGalileoPath = std::string(DEEPNAV_SOURCE_DIR) + "/data/galileo_20220220.rnx";

const NavData& galileo_nav() {
  static const NavData nav = read_rinex_nav(kGalileoPath);
  return nav;
}

std::vector<std::string> file_lines() {
  std::ifstream f(kGalileoPath);
  std::vector<std::string> lines;
  for (std::string line; std::getline(f, line);) lines.push_back(line);
  return lines;
}

/// The header and the first record of the file with line `index` (0-based, counted from the
/// file's start) replaced by `replacement`.
std::string first_record_with(std::size_t index, const std::string& replacement) {
  auto lines = file_lines();
  lines[index] = replacement;
  std::string text;
  for (std::size_t i = 0; i < 15; ++i) text += lines[i] + "\n";
  return text;
}

std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    read_rinex_nav(in, "gal.rnx");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(RinexNavGalileo, ReadsTheHeader) {
  const NavData& nav = galileo_nav();
  EXPECT_DOUBLE_EQ(nav.rinex_version, 3.04);
  ASSERT_TRUE(nav.galileo_iono.valid);
  EXPECT_DOUBLE_EQ(nav.galileo_iono.ai0_sfu, 81.25);
  EXPECT_DOUBLE_EQ(nav.galileo_iono.ai1_sfu_per_deg, -2.4609E-01);
  EXPECT_DOUBLE_EQ(nav.galileo_iono.ai2_sfu_per_deg2, 3.7537E-03);
  ASSERT_TRUE(nav.ggto.valid);
  EXPECT_DOUBLE_EQ(nav.ggto.a0g_s, 5.9080775827E-09);
  EXPECT_DOUBLE_EQ(nav.ggto.a1g_sps, 3.552713679E-15);
  EXPECT_EQ(nav.ggto.t0g_s, 86400);
  EXPECT_EQ(nav.ggto.wn0g, 2198 - 1024);  // the file's GPS-numbered week as a GST week
  ASSERT_TRUE(nav.galileo_utc.valid);
  EXPECT_DOUBLE_EQ(nav.galileo_utc.a0_s, -9.3132257462E-10);
  EXPECT_DOUBLE_EQ(nav.galileo_utc.a1_sps, 8.881784197E-16);
  EXPECT_EQ(nav.galileo_utc.tot_s, 0);
  EXPECT_EQ(nav.galileo_utc.wnt, 1174);
  EXPECT_EQ(nav.utc.delta_t_ls, 18);
  EXPECT_FALSE(nav.iono.valid);  // no GPS lines
  EXPECT_TRUE(nav.ephemerides.empty());
  EXPECT_EQ(nav.skipped_records, 0);
}

TEST(RinexNavGalileo, ReadsEveryRecordWithItsFields) {
  const NavData& nav = galileo_nav();
  ASSERT_EQ(nav.galileo_ephemerides.size(), 120u);
  const galileo::GalileoEphemeris& e = nav.galileo_ephemerides.front();  // E01 2022 02 19 22 00 00
  EXPECT_EQ(e.prn, 1);
  EXPECT_EQ(e.week, 2197 - 1024);
  EXPECT_DOUBLE_EQ(e.toc_s, 597600.0);
  EXPECT_DOUBLE_EQ(e.af0_s, -5.823274259456E-04);
  EXPECT_DOUBLE_EQ(e.af1_sps, -7.318590178329E-12);
  EXPECT_EQ(e.iod_nav, 100);
  EXPECT_DOUBLE_EQ(e.orbit.crs_m, 3.634375000000E+01);
  EXPECT_DOUBLE_EQ(e.orbit.sqrt_a, 5.440600259781E+03);
  EXPECT_DOUBLE_EQ(e.orbit.toe_s, 597600.0);
  EXPECT_DOUBLE_EQ(e.orbit.omega_dot_radps, -6.031679815103E-09);
  EXPECT_DOUBLE_EQ(e.orbit.idot_radps, 1.446488823494E-10);
  EXPECT_EQ(e.data_sources, 517);  // I/NAV E1-B and E5b, clock for E5b,E1
  EXPECT_EQ(e.sisa_index, 107);    // 3.12 m
  EXPECT_TRUE(e.healthy_on_e1b());
  EXPECT_DOUBLE_EQ(e.bgd_e1e5a_s, 2.328306436539E-10);
  EXPECT_DOUBLE_EQ(e.bgd_e1e5b_s, 0.0);
  EXPECT_TRUE(e.transmission_time_known);
  EXPECT_DOUBLE_EQ(e.transmission_time_s, 5.982650000000E+05);
  // Both navigation messages' data sets are there.
  int inav = 0, fnav = 0;
  for (const auto& r : nav.galileo_ephemerides) {
    inav += (r.data_sources & 1) != 0;
    fnav += (r.data_sources & 2) != 0;
  }
  EXPECT_GT(inav, 0);
  EXPECT_GT(fnav, 0);
  EXPECT_EQ(inav + fnav, 120);
}

TEST(RinexNavGalileo, HealthBitsPerSignal) {
  // E18 (health 130 in I/NAV records: E1-B and E5b out of service) and E10 (455: E1-B and E5b
  // in test, data without guarantee; 56 in F/NAV records: E5a alike).
  int checked = 0;
  for (const auto& e : galileo_nav().galileo_ephemerides) {
    if (e.prn == 18 && (e.data_sources & 1)) {
      EXPECT_EQ(e.e1b.health, static_cast<int>(galileo::SignalHealth::kOutOfService));
      EXPECT_FALSE(e.e1b.data_invalid);
      EXPECT_EQ(e.e5b.health, 1);
      EXPECT_FALSE(e.healthy_on_e1b());
      ++checked;
    }
    if (e.prn == 10 && (e.data_sources & 1)) {
      EXPECT_EQ(e.e1b.health, 3);
      EXPECT_TRUE(e.e1b.data_invalid);
      EXPECT_EQ(e.e5b.health, 3);
      EXPECT_TRUE(e.e5b.data_invalid);
      ++checked;
    }
    if (e.prn == 10 && (e.data_sources & 2)) {
      EXPECT_EQ(e.e5a.health, 3);
      EXPECT_TRUE(e.e5a.data_invalid);
      EXPECT_TRUE(e.e1b.usable());  // bits of other signals are zero in an F/NAV record
      ++checked;
    }
  }
  EXPECT_GE(checked, 3);
}

TEST(RinexNavGalileo, SuccessiveBatchesAgreeOnTheOrbit) {
  // Two I/NAV data sets of one healthy satellite, evaluated halfway between their toe: real
  // broadcast orbits agree to about a metre (millimetres per second) and clocks to about a
  // nanosecond. A wrong constant,
  // week or reference time in the model would not.
  std::map<int, std::vector<const galileo::GalileoEphemeris*>> by_prn;
  for (const auto& e : galileo_nav().galileo_ephemerides) {
    if ((e.data_sources & 1) && e.healthy_on_e1b()) by_prn[e.prn].push_back(&e);
  }
  int pairs = 0;
  for (const auto& [prn, sets] : by_prn) {
    for (std::size_t i = 1; i < sets.size(); ++i) {
      const galileo::GalileoEphemeris &a = *sets[i - 1], &b = *sets[i];
      const galileo::GstTime ta{a.week, a.orbit.toe_s}, tb{b.week, b.orbit.toe_s};
      const double gap = tb.seconds_since(ta);
      if (gap == 0.0 || std::abs(gap) > 4 * 3600.0) continue;
      const galileo::GstTime mid = galileo::GstTime::normalized(a.week, a.orbit.toe_s + gap / 2);
      const SatelliteState sa = galileo::satellite_state(a, mid), sb = galileo::satellite_state(b, mid);
      EXPECT_LT((sa.r_ecef_m - sb.r_ecef_m).norm(), 3.0) << "E" << prn << " gap " << gap;
      EXPECT_LT((sa.v_ecef_mps - sb.v_ecef_mps).norm(), 5e-3) << "E" << prn;
      EXPECT_LT(std::abs(galileo::e1_clock_correction_s(a, mid) - galileo::e1_clock_correction_s(b, mid)), 3e-9)
          << "E" << prn;
      ++pairs;
    }
  }
  EXPECT_GE(pairs, 20);
}

TEST(RinexNavGalileo, BadValuesAreNamed) {
  // Line 8 is E01's epoch line, 9..15 its orbit lines.
  const auto lines = file_lines();
  ASSERT_EQ(lines[7].substr(0, 3), "E01");
  EXPECT_EQ(error_of(first_record_with(0, lines[0])), "");  // the cut file itself reads
  // Crs beyond its 16-bit field of 1/32 m.
  std::string crs = lines[8];
  crs.replace(23, 19, " 2.000000000000E+03");
  const std::string crs_error = error_of(first_record_with(8, crs));
  EXPECT_NE(crs_error.find("gal.rnx:"), std::string::npos) << crs_error;
  EXPECT_NE(crs_error.find("E01"), std::string::npos) << crs_error;
  EXPECT_NE(crs_error.find("Crs = 2000"), std::string::npos) << crs_error;
  // A PRN without a Galileo code.
  std::string prn = lines[7];
  prn.replace(1, 2, "51");
  EXPECT_NE(error_of(first_record_with(7, prn)).find("PRN"), std::string::npos);
  // A GAL week before GST began.
  std::string week = lines[12];
  week.replace(42, 19, " 1.000000000000E+03");
  EXPECT_NE(error_of(first_record_with(12, week)).find("GAL week"), std::string::npos);
  // Health with bits no signal has.
  std::string health = lines[13];
  health.replace(23, 19, " 1.024000000000E+03");
  EXPECT_NE(error_of(first_record_with(13, health)).find("SV health"), std::string::npos);
  // An ionosphere coefficient outside its field.
  std::string iono = lines[2];
  iono.replace(5, 12, "  9.0000E+02");
  const std::string iono_error = error_of(first_record_with(2, iono));
  EXPECT_NE(iono_error.find("a_i0 = 900"), std::string::npos) << iono_error;
  // A truncated record.
  auto cut = file_lines();
  std::string text;
  for (std::size_t i = 0; i < 12; ++i) text += cut[i] + "\n";
  EXPECT_NE(error_of(text).find("truncated"), std::string::npos);
}

}  // namespace
}  // namespace deepnav
