#include "signals/ca_code.hpp"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <stdexcept>
#include <vector>

namespace deepnav {
namespace {

// IS-GPS-200 Table 3-I, "First 10 Chips Octal" for C/A PRN 1..32: the leading 1 is the first
// chip, the three following octal digits are chips 2..10.
constexpr std::array<int, 32> kFirstTenChipsOctal = {
    01440, 01620, 01710, 01744, 01133, 01455, 01131, 01454, 01626, 01504, 01642, 01750, 01764, 01772, 01775, 01776,
    01156, 01467, 01633, 01715, 01746, 01763, 01063, 01706, 01743, 01761, 01770, 01774, 01127, 01453, 01625, 01712,
};

int first_ten_chips(const CaCodeBits& bits) {
  int value = 0;
  for (int i = 0; i < 10; ++i) value = (value << 1) | bits[i];
  return value;
}

// Circular correlation of two +-1 codes at every lag.
std::vector<int> circular_correlation(const CaCodeChips& a, const CaCodeChips& b) {
  std::array<int, 2 * 1023> b2{};
  for (int i = 0; i < 1023; ++i) b2[i] = b2[i + 1023] = b[i];
  std::vector<int> out(1023);
  for (int lag = 0; lag < 1023; ++lag) {
    int sum = 0;
    for (int i = 0; i < 1023; ++i) sum += a[i] * b2[i + lag];
    out[lag] = sum;
  }
  return out;
}

bool three_valued(int r) { return r == -65 || r == -1 || r == 63; }

TEST(CaCode, FirstTenChipsMatchTable3I) {
  for (int prn = 1; prn <= 32; ++prn) {
    EXPECT_EQ(first_ten_chips(ca_code_bits(prn)), kFirstTenChipsOctal[prn - 1]) << "PRN " << prn;
  }
}

TEST(CaCode, ChipsAreSignalLevelsOfBits) {
  for (int prn : {1, 17, 32}) {
    const auto bits = ca_code_bits(prn);
    const auto& chips = ca_code_chips(prn);
    for (int i = 0; i < 1023; ++i) ASSERT_EQ(chips[i], bits[i] ? -1 : 1) << "PRN " << prn << " chip " << i;
  }
}

TEST(CaCode, BalancedGoldCodes) {
  // Balanced Gold codes have 512 ones; all C/A codes 1..32 are balanced.
  for (int prn = 1; prn <= 32; ++prn) {
    int ones = 0;
    for (auto b : ca_code_bits(prn)) ones += b;
    EXPECT_EQ(ones, 512) << "PRN " << prn;
  }
}

TEST(CaCode, AutocorrelationPeakAndSidelobes) {
  for (int prn = 1; prn <= 32; ++prn) {
    const auto r = circular_correlation(ca_code_chips(prn), ca_code_chips(prn));
    EXPECT_EQ(r[0], 1023) << "PRN " << prn;
    for (int lag = 1; lag < 1023; ++lag)
      ASSERT_TRUE(three_valued(r[lag])) << "PRN " << prn << " lag " << lag << ": " << r[lag];
  }
}

TEST(CaCode, CrossCorrelationIsThreeValued) {
  std::set<int> seen;
  for (int a = 1; a <= 32; ++a) {
    for (int b = a + 1; b <= 32; ++b) {
      const auto r = circular_correlation(ca_code_chips(a), ca_code_chips(b));
      for (int lag = 0; lag < 1023; ++lag) {
        ASSERT_TRUE(three_valued(r[lag])) << "PRN " << a << " x " << b << " lag " << lag << ": " << r[lag];
        seen.insert(r[lag]);
      }
    }
  }
  EXPECT_EQ(seen, (std::set<int>{-65, -1, 63}));
}

TEST(CaCode, RejectsPrnOutsideRange) {
  EXPECT_THROW(ca_code_bits(0), std::invalid_argument);
  EXPECT_THROW(ca_code_bits(33), std::invalid_argument);
  EXPECT_THROW(ca_code_chips(-1), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
