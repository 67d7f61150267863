#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "signals/galileo/crc24q.hpp"
#include "signals/galileo/inav_fec.hpp"

namespace deepnav::galileo::inav {
namespace {

PagePartBits random_bits(unsigned seed) {
  std::mt19937 rng(seed);
  PagePartBits bits{};
  for (auto& b : bits) b = static_cast<std::uint8_t>(rng() & 1);
  return bits;
}

/// Signal levels of hard symbols: logic 0 -> +1, logic 1 -> -1.
PagePartSoftSymbols levels(const PagePartSymbols& symbols) {
  PagePartSoftSymbols out{};
  for (std::size_t i = 0; i < symbols.size(); ++i) out[i] = symbols[i] ? -1.0f : 1.0f;
  return out;
}

TEST(GalileoCrc24q, StandardCheckValue) {
  // The catalogued check value of this CRC (poly 0x864CFB, init 0, no reflection, no final
  // XOR) over the ASCII digits "123456789" is 0xCDE703.
  std::vector<std::uint8_t> bits;
  for (char c : std::string("123456789")) {
    for (int k = 7; k >= 0; --k) bits.push_back(static_cast<std::uint8_t>((c >> k) & 1));
  }
  EXPECT_EQ(crc24q(bits), 0xCDE703u);
  EXPECT_EQ(crc24q({}), 0u);
  // A message followed by its CRC leaves no remainder.
  const std::uint32_t crc = crc24q(bits);
  for (int k = 23; k >= 0; --k) bits.push_back(static_cast<std::uint8_t>((crc >> k) & 1));
  EXPECT_EQ(crc24q(bits), 0u);
}

TEST(GalileoInavFec, ImpulseResponseIsTheGeneratorsWithG2Inverted) {
  // A single 1 walks through the register: G1's symbols read 171 octal (1111001) and G2's
  // 133 octal (1011011) inverted (0100100); zeros after it give G1 0 and inverted G2 1.
  PagePartBits bits{};
  bits[0] = 1;
  const PagePartSymbols s = convolutional_encode(bits);
  const std::string g1 = "1111001", g2_inverted = "0100100";
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(s[2 * i], g1[i] - '0') << "G1 symbol " << i;
    EXPECT_EQ(s[2 * i + 1], g2_inverted[i] - '0') << "G2 symbol " << i;
  }
  for (int i = 7; i < kPagePartSymbols / 2; ++i) {
    EXPECT_EQ(s[2 * i], 0) << i;
    EXPECT_EQ(s[2 * i + 1], 1) << i;
  }
}

TEST(GalileoInavFec, TheCodeIsLinearOverItsInvertedOffset) {
  // Encoding is linear up to the constant inversion of G2: c(a xor b) = c(a) xor c(b) xor c(0).
  const PagePartBits a = random_bits(1), b = random_bits(2);
  PagePartBits sum{};
  for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = a[i] ^ b[i];
  const PagePartSymbols ca = convolutional_encode(a), cb = convolutional_encode(b), c0 = convolutional_encode({});
  const PagePartSymbols csum = convolutional_encode(sum);
  for (std::size_t i = 0; i < csum.size(); ++i) EXPECT_EQ(csum[i], ca[i] ^ cb[i] ^ c0[i]) << i;
}

TEST(GalileoInavFec, InterleaverWritesColumnsOfEightAndReadsRowsOfThirty) {
  PagePartSymbols coded{};
  coded[1] = 1;  // second symbol of column 0: row 1 -> sent 31st
  coded[8] = 1;  // first symbol of column 1: row 0 -> sent 2nd
  const PagePartSymbols sent = interleave(coded);
  for (int i = 0; i < kPagePartSymbols; ++i) EXPECT_EQ(sent[i], (i == 30 || i == 1) ? 1 : 0) << i;
  // deinterleave undoes it.
  const PagePartSoftSymbols back = deinterleave(levels(interleave(convolutional_encode(random_bits(3)))));
  EXPECT_EQ(back, levels(convolutional_encode(random_bits(3))));
}

TEST(GalileoInavFec, RoundTripWithoutNoise) {
  for (unsigned seed = 10; seed < 20; ++seed) {
    const PagePartBits bits = random_bits(seed);
    EXPECT_EQ(decode_page_part(levels(encode_page_part(bits))), bits) << "seed " << seed;
  }
  EXPECT_EQ(decode_page_part(levels(encode_page_part({}))), PagePartBits{});
}

TEST(GalileoInavFec, CorrectsNoiseBurstsAndErasures) {
  std::mt19937 rng(42);
  // Gaussian noise of sigma 0.6 on +/-1 symbols: about 5 % of the hard decisions wrong.
  std::normal_distribution<float> noise(0.0f, 0.6f);
  int hard_errors = 0;
  for (unsigned seed = 100; seed < 120; ++seed) {
    const PagePartBits bits = random_bits(seed);
    PagePartSoftSymbols rx = levels(encode_page_part(bits));
    for (auto& s : rx) {
      const float sent = s;
      s += noise(rng);
      hard_errors += (s > 0) != (sent > 0);
    }
    EXPECT_EQ(decode_page_part(rx), bits) << "noise, seed " << seed;
  }
  EXPECT_GT(hard_errors, 20 * kPagePartSymbols / 50);  // the noise did flip symbols
  // A burst of 8 flipped symbols in a row: the interleaver spreads it 30 coded symbols apart.
  const PagePartBits bits = random_bits(7);
  PagePartSoftSymbols burst = levels(encode_page_part(bits));
  for (int i = 100; i < 108; ++i) burst[i] = -burst[i];
  EXPECT_EQ(decode_page_part(burst), bits);
  // Soft decisions: a third of the symbols erased (level 0) costs nothing here.
  PagePartSoftSymbols erased = levels(encode_page_part(bits));
  for (int i = 0; i < kPagePartSymbols; i += 3) erased[i] = 0.0f;
  EXPECT_EQ(decode_page_part(erased), bits);
  // Any scale of the levels decodes alike.
  PagePartSoftSymbols scaled = levels(encode_page_part(bits));
  for (auto& s : scaled) s *= 1234.5f;
  EXPECT_EQ(decode_page_part(scaled), bits);
}

TEST(GalileoInavFec, TooManyErrorsDecodeWrong) {
  // Half the symbols inverted: beyond any code's reach, the decoder must not return the data
  // (the page CRC is what tells the caller).
  const PagePartBits bits = random_bits(8);
  PagePartSoftSymbols rx = levels(encode_page_part(bits));
  for (int i = 0; i < kPagePartSymbols; i += 2) rx[i] = -rx[i];
  EXPECT_NE(decode_page_part(rx), bits);
}

}  // namespace
}  // namespace deepnav::galileo::inav
