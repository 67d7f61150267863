#include <gtest/gtest.h>

#include <algorithm>
#include <bitset>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "signals/galileo/e1_code_tables.hpp"
#include "signals/galileo/e1_codes.hpp"

namespace deepnav::galileo {
namespace {

using CodeBits = std::bitset<kE1CodeLength_chips>;

CodeBits logic_ones(const E1CodeChips& chips) {
  CodeBits bits;
  for (std::size_t i = 0; i < chips.size(); ++i) bits[i] = chips[i] < 0;
  return bits;
}

/// Circular correlation sum_i a[i] b[i + lag] of two +/-1 codes from their logic bits.
int circular_correlation(const CodeBits& a, const CodeBits& b, int lag) {
  const CodeBits shifted =
      (b >> static_cast<std::size_t>(lag)) | (b << static_cast<std::size_t>(kE1CodeLength_chips - lag));
  return kE1CodeLength_chips - 2 * static_cast<int>((a ^ shifted).count());
}

/// Largest |correlation| over all lags (lag 0 left out for a code with itself).
int peak_correlation(const CodeBits& a, const CodeBits& b, bool same_code) {
  int peak = 0;
  for (int lag = same_code ? 1 : 0; lag < kE1CodeLength_chips; ++lag) {
    peak = std::max(peak, std::abs(circular_correlation(a, b, lag)));
  }
  return peak;
}

// The memory codes were optimised for low correlation; every published one stays below
// -24 dB (about 258 of 4092) at every lag. A wrong digit anywhere would not keep them all
// there and exactly balanced.
constexpr int kMaxSidelobe = 258;

TEST(GalileoE1Codes, ChipOrderIsMostSignificantBitFirst) {
  // E1-B PRN 1 starts F5D7 (ICD Annex C): 1111 0101 ..., logic 1 -> -1.
  const E1CodeChips& b1 = e1b_code_chips(1);
  const std::int8_t expected[8] = {-1, -1, -1, -1, 1, -1, 1, -1};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(b1[static_cast<std::size_t>(i)], expected[i]) << "chip " << i;
  // E1-C PRN 50 ends ...BD0C: 1011 1101 0000 1100.
  const E1CodeChips& c50 = e1c_code_chips(50);
  const std::int8_t tail[16] = {-1, 1, -1, -1, -1, -1, 1, -1, 1, 1, 1, 1, -1, -1, 1, 1};
  for (int i = 0; i < 16; ++i) EXPECT_EQ(c50[static_cast<std::size_t>(kE1CodeLength_chips - 16 + i)], tail[i]);
}

TEST(GalileoE1Codes, TablesAreTheCrossCheckedOnes) {
  // FNV-1a (64 bit) of the 100 hexadecimal strings, E1-B PRN 1..50 then E1-C PRN 1..50, as
  // compared with GNSS-SDR 0.0.17 and GNSS-DSP-tools (see e1_code_tables.cpp): an edit of
  // the tables shows here.
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const auto* table : {&detail::kE1bPrimaryHex, &detail::kE1cPrimaryHex}) {
    for (std::string_view code : *table) {
      for (char c : code) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
    }
  }
  EXPECT_EQ(hash, 0xaa1066222ca25206ULL);
}

TEST(GalileoE1Codes, EveryCodeIsBalanced) {
  for (int prn = 1; prn <= kMaxPrn; ++prn) {
    EXPECT_EQ(logic_ones(e1b_code_chips(prn)).count(), 2046u) << "E1-B PRN " << prn;
    EXPECT_EQ(logic_ones(e1c_code_chips(prn)).count(), 2046u) << "E1-C PRN " << prn;
  }
}

TEST(GalileoE1Codes, AutocorrelationHasOnePeak) {
  for (int prn = 1; prn <= kMaxPrn; ++prn) {
    for (const CodeBits& code : {logic_ones(e1b_code_chips(prn)), logic_ones(e1c_code_chips(prn))}) {
      EXPECT_EQ(circular_correlation(code, code, 0), kE1CodeLength_chips);
      EXPECT_LE(peak_correlation(code, code, true), kMaxSidelobe) << "PRN " << prn;
    }
  }
}

TEST(GalileoE1Codes, CrossCorrelationIsLow) {
  // Neighbouring PRNs of each component, and the two components of one satellite.
  for (int prn = 1; prn <= kMaxPrn; ++prn) {
    const CodeBits b = logic_ones(e1b_code_chips(prn));
    const CodeBits c = logic_ones(e1c_code_chips(prn));
    EXPECT_LE(peak_correlation(b, c, false), kMaxSidelobe) << "E1-B/E1-C PRN " << prn;
    if (prn == kMaxPrn) continue;
    EXPECT_LE(peak_correlation(b, logic_ones(e1b_code_chips(prn + 1)), false), kMaxSidelobe) << "E1-B PRN " << prn;
    EXPECT_LE(peak_correlation(c, logic_ones(e1c_code_chips(prn + 1)), false), kMaxSidelobe) << "E1-C PRN " << prn;
  }
}

TEST(GalileoE1Codes, SecondaryCodeIsCs25) {
  // ICD Table 16 prints CS25 in hexadecimal (380AD90); in bits 0011100000001010110110010.
  const std::string bits = "0011100000001010110110010";
  const E1SecondaryChips& cs25 = e1c_secondary_chips();
  for (std::size_t i = 0; i < bits.size(); ++i) EXPECT_EQ(cs25[i], bits[i] == '1' ? -1 : 1) << "chip " << i;
}

TEST(GalileoE1Codes, RejectsPrnsWithoutCodeAndBadHex) {
  for (int prn : {0, -1, 51}) {
    EXPECT_THROW(e1b_code_chips(prn), std::invalid_argument);
    EXPECT_THROW(e1c_code_chips(prn), std::invalid_argument);
  }
  try {
    e1b_code_chips(51);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("PRN 51 is not in 1..50"), std::string::npos) << e.what();
  }
  EXPECT_THROW(chips_from_hex("38G", 12, "test"), std::invalid_argument);  // not a digit
  EXPECT_THROW(chips_from_hex("380", 8, "test"), std::invalid_argument);   // length
  EXPECT_THROW(chips_from_hex("381", 11, "test"), std::invalid_argument);  // padding bit set
  EXPECT_EQ(chips_from_hex("380", 11, "test").size(), 11u);
}

}  // namespace
}  // namespace deepnav::galileo
