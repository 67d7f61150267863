#include "signals/lnav_parity.hpp"

#include <gtest/gtest.h>

#include <random>

namespace deepnav::lnav {
namespace {

// Hand-evaluated from Table 20-XIV: TLM word with preamble 10001011 and zero message,
// D29* = D30* = 0. Ones in d1, d5, d7, d8 give D25..D30 = 0 1 0 0 1 0.
constexpr std::uint32_t kTlmData = 0x8B0000;
constexpr std::uint32_t kTlmWord = (kTlmData << 6) | 0b010010;

TEST(LnavParity, KnownTlmWord) {
  EXPECT_EQ(parity_bits(kTlmData, false, false), 0b010010u);
  EXPECT_EQ(encode_word(kTlmData, false, false), kTlmWord);
  ASSERT_TRUE(check_word(kTlmWord, false, false).has_value());
  EXPECT_EQ(*check_word(kTlmWord, false, false), kTlmData);
}

TEST(LnavParity, KnownWordWithPreviousBitsSet) {
  // D29* = D30* = 1: every equation gains a one, so each parity bit flips, and the data are
  // sent complemented.
  EXPECT_EQ(parity_bits(kTlmData, true, true), 0b101101u);
  EXPECT_EQ(encode_word(kTlmData, true, true), ((~kTlmData & kDataMask) << 6) | 0b101101u);
  // Only D29*: D25, D27, D30 flip.
  EXPECT_EQ(parity_bits(kTlmData, true, false), 0b111011u);
  // Only D30*: D26, D28, D29 flip, and the data bits go out complemented.
  EXPECT_EQ(parity_bits(kTlmData, false, true), 0b000100u);
  EXPECT_EQ(encode_word(kTlmData, false, true) >> 6, ~kTlmData & kDataMask);
}

TEST(LnavParity, AllZeroAndSingleBitData) {
  EXPECT_EQ(encode_word(0, false, false), 0u);
  // d24 alone enters D26, D29 and D30.
  EXPECT_EQ(parity_bits(1, false, false), 0b010011u);
  // d1 alone enters D25, D27 and D29.
  EXPECT_EQ(parity_bits(1u << 23, false, false), 0b101010u);
}

TEST(LnavParity, RoundTripAndComplementRestoresData) {
  std::mt19937_64 rng(42);
  for (int i = 0; i < 2000; ++i) {
    const auto data = static_cast<std::uint32_t>(rng()) & kDataMask;
    const bool p29 = rng() & 1, p30 = rng() & 1;
    const auto word = encode_word(data, p29, p30);
    ASSERT_LE(word, kWordMask);
    const auto back = check_word(word, p29, p30);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, data);
    EXPECT_EQ((word >> 6) == data, !p30);
  }
}

TEST(LnavParity, EverySingleBitErrorIsDetected) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 300; ++i) {
    const auto data = static_cast<std::uint32_t>(rng()) & kDataMask;
    const bool p29 = rng() & 1, p30 = rng() & 1;
    const auto word = encode_word(data, p29, p30);
    for (int bit = 0; bit < 30; ++bit) {
      EXPECT_FALSE(check_word(word ^ (1u << bit), p29, p30).has_value()) << "bit " << bit;
    }
    // A wrong D30* alone flips D26, D28, D29 and the data: detected as well; so is a wrong D29*.
    EXPECT_FALSE(check_word(word, p29, !p30).has_value());
    EXPECT_FALSE(check_word(word, !p29, p30).has_value());
  }
}

TEST(LnavParity, InvertedWordWithInvertedPreviousBitsChecks) {
  // A stream received with inverted polarity passes parity word by word and yields the
  // same data (the receiver resolves the sign from the preamble).
  std::mt19937_64 rng(9);
  for (int i = 0; i < 500; ++i) {
    const auto data = static_cast<std::uint32_t>(rng()) & kDataMask;
    const bool p29 = rng() & 1, p30 = rng() & 1;
    const auto inverted = ~encode_word(data, p29, p30) & kWordMask;
    const auto back = check_word(inverted, !p29, !p30);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, data);
  }
}

TEST(LnavParity, NonInformationBitsZeroTheLastTwoBits) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 1000; ++i) {
    const auto data = static_cast<std::uint32_t>(rng()) & kDataMask;
    const bool p29 = rng() & 1, p30 = rng() & 1;
    const auto solved = with_noninformation_bits(data, p29, p30);
    EXPECT_EQ(solved & ~0x3u, data & ~0x3u);  // d1..d22 untouched
    const auto word = encode_word(solved, p29, p30);
    EXPECT_FALSE(word_d29(word));
    EXPECT_FALSE(word_d30(word));
  }
}

}  // namespace
}  // namespace deepnav::lnav
