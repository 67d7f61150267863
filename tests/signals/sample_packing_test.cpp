// Packed sample formats: the layouts GNSS-SDR's unpackers read (two_bit_packed and its
// item/bit orders, two_bit_cpx, four_bit_cpx), the encodings, every layout's pack/unpack
// round trip, and the names (parse, canonical name, aliases, errors).
#include "signals/sample_packing.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "signals/sample_format.hpp"

namespace deepnav {
namespace {

std::vector<int> unpack(const std::string& format_name, std::vector<std::uint8_t> bytes) {
  const SampleFormat f = parse_sample_format(format_name);
  EXPECT_TRUE(is_packed(f)) << format_name;
  std::vector<std::byte> in(bytes.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) in[i] = static_cast<std::byte>(bytes[i]);
  std::vector<std::int16_t> levels(bytes.size() / static_cast<std::size_t>(f.packed.word_bytes) *
                                   values_per_word(f.packed));
  unpack_levels(in, f.packed, levels);
  return {levels.begin(), levels.end()};
}

std::string error_of(const std::string& name) {
  try {
    parse_sample_format(name);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SamplePacking, TwoBitPackedReadsAsGnssSdrDoes) {
  // GNSS-SDR's two_bit_packed (byte items, big_endian_bytes=false): the first value of a
  // byte in bits 1..0, two's complement x read as 2x + 1: 00 +1, 01 +3, 10 -3, 11 -1.
  EXPECT_EQ(unpack("two_bit_packed", {0xE4}), (std::vector<int>{1, 3, -3, -1}));
  EXPECT_EQ(unpack("packed2", {0xE4, 0x1B}), (std::vector<int>{1, 3, -3, -1, -1, -3, 3, 1}));
  // big_endian_bytes=true: the first value in bits 7..6.
  EXPECT_EQ(unpack("packed2_msb", {0xE4}), (std::vector<int>{-1, -3, 3, 1}));
  // Short items, big endian (GNSS-SDR's default for shorts): the bytes of each 16-bit item
  // are swapped, then read from the least significant bits; little-endian shorts read as bytes.
  EXPECT_EQ(unpack("packed2_w16be", {0x1B, 0xE4}), (std::vector<int>{1, 3, -3, -1, -1, -3, 3, 1}));
  EXPECT_EQ(unpack("packed2_w16le", {0xE4, 0x1B}), unpack("packed2", {0xE4, 0x1B}));
  // Big-endian shorts with big_endian_bytes=true: swapped, then each byte from its top bits.
  EXPECT_EQ(unpack("packed2_bytemsb_w16be", {0x1B, 0xE4}), (std::vector<int>{-1, -3, 3, 1, 1, 3, -3, -1}));
  // Whole-word orders: from the top of the 16-bit word down, and up from its bottom.
  EXPECT_EQ(unpack("packed2_msb_w16le", {0x1B, 0xE4}), (std::vector<int>{-1, -3, 3, 1, 1, 3, -3, -1}));
  EXPECT_EQ(unpack("packed4_w32le", {0x10, 0x32, 0x54, 0x76}), (std::vector<int>{1, 3, 5, 7, 9, 11, 13, 15}));
  EXPECT_EQ(unpack("packed4_msb_w32be", {0x10, 0x32, 0x54, 0x76}), (std::vector<int>{3, 1, 7, 5, 11, 9, 15, 13}));
}

TEST(SamplePacking, ComplexLayoutsOfGnssSdr) {
  // two_bit_cpx (GNSS-SDR's unpack_byte_2bit_cpx_samples): Q[n] in bits 7..6, I[n] 5..4,
  // Q[n+1] 3..2, I[n+1] 1..0. 0b01'10'11'00: Q0 +3, I0 -3, Q1 -1, I1 +1.
  const SampleFormat cpx = parse_sample_format("two_bit_cpx");
  EXPECT_EQ(to_string(cpx), "packed2_qi_msb");
  EXPECT_EQ(samples_per_word(cpx), 2u);
  EXPECT_EQ(unpack("two_bit_cpx", {0b01101100}), (std::vector<int>{3, -3, -1, 1}));  // in file order: Q0 I0 Q1 I1
  // four_bit_cpx (unpack_byte_4bit_samples, iq): I in the low nibble, Q in the high one.
  EXPECT_EQ(to_string(parse_sample_format("four_bit_cpx")), "packed4_iq");
  EXPECT_EQ(unpack("four_bit_cpx", {0x7F, 0x80}), (std::vector<int>{-1, 15, 1, -15}));
  // two_bit_packed with sample_type iq: I from bits 1..0, Q from 3..2.
  EXPECT_EQ(unpack("two_bit_packed_iq", {0xE4}), (std::vector<int>{1, 3, -3, -1}));
  EXPECT_EQ(to_string(parse_sample_format("two_bit_packed_iq")), "packed2_iq");
  EXPECT_EQ(samples_per_word(parse_sample_format("packed2_iq")), 2u);
  EXPECT_EQ(samples_per_word(parse_sample_format("packed1_w32le")), 32u);
}

TEST(SamplePacking, Encodings) {
  // 2 bits, codes 00, 01, 10, 11 in that order (lsb first: 0b11'10'01'00).
  EXPECT_EQ(unpack("packed2", {0xE4}), (std::vector<int>{1, 3, -3, -1}));
  EXPECT_EQ(unpack("packed2_sm", {0xE4}), (std::vector<int>{1, 3, -1, -3}));
  EXPECT_EQ(unpack("packed2_ob", {0xE4}), (std::vector<int>{-3, -1, 1, 3}));
  // 1 bit: the sign (1 negative) for two's complement and sign/magnitude; offset binary 1 positive.
  EXPECT_EQ(unpack("packed1", {0x0F}), (std::vector<int>{-1, -1, -1, -1, 1, 1, 1, 1}));
  EXPECT_EQ(unpack("packed1_sm", {0x0F}), (std::vector<int>{-1, -1, -1, -1, 1, 1, 1, 1}));
  EXPECT_EQ(unpack("packed1_ob", {0x0F}), (std::vector<int>{1, 1, 1, 1, -1, -1, -1, -1}));
  // 4 bits: sign/magnitude 0b1111 is -15, 0b0111 is +15; offset binary 0 is -15.
  EXPECT_EQ(unpack("packed4_sm", {0x7F}), (std::vector<int>{-15, 15}));
  EXPECT_EQ(unpack("packed4_ob", {0xF0}), (std::vector<int>{-15, 15}));
}

TEST(SamplePacking, EveryLayoutRoundTrips) {
  std::mt19937 rng(7);
  int layouts = 0;
  for (const int bits : {1, 2, 4})
    for (const char* type : {"", "_iq", "_qi"})
      for (const char* encoding : {"", "_sm", "_ob"})
        for (const char* order : {"", "_msb", "_bytemsb"})
          for (const char* word : {"", "_w16le", "_w16be", "_w32le", "_w32be"}) {
            const std::string name = "packed" + std::to_string(bits) + type + encoding + order + word;
            const SampleFormat f = parse_sample_format(name);
            ASSERT_EQ(parse_sample_format(to_string(f)), f) << name << " -> " << to_string(f);
            const std::size_t words = 5, n = words * values_per_word(f.packed);
            std::vector<std::int16_t> levels(n), back(n);
            const int max_code = (1 << bits) - 1;
            for (auto& v : levels)
              v = static_cast<std::int16_t>(2 * std::uniform_int_distribution<int>(0, max_code)(rng) - max_code);
            std::vector<std::byte> bytes(words * bytes_per_word(f));
            pack_levels(levels, f.packed, bytes);
            unpack_levels(bytes, f.packed, back);
            ASSERT_EQ(back, levels) << name;
            ++layouts;
          }
  EXPECT_EQ(layouts, 405);
}

TEST(SamplePacking, NamesAndErrors) {
  EXPECT_EQ(to_string(parse_sample_format("packed2_real_tc_lsb_w8")), "packed2");
  EXPECT_EQ(to_string(parse_sample_format("packed2_bytemsb")), "packed2_msb");    // one byte: the same order
  EXPECT_EQ(to_string(parse_sample_format("two_bit_cpx_iq")), "packed2_iq_msb");  // the user's token wins
  EXPECT_EQ(parse_sample_format("cs8"), SampleFormat::ibyte);
  EXPECT_NE(error_of("packed3").find("1, 2 or 4 bits"), std::string::npos);
  EXPECT_NE(error_of("packed2_iqq").find("unknown token 'iqq'"), std::string::npos);
  EXPECT_NE(error_of("packed2_iq_qi").find("'qi' repeats"), std::string::npos);
  EXPECT_NE(error_of("packed2_").find("unknown token '(empty)'"), std::string::npos);
  EXPECT_NE(error_of("cs9").find("expected one of"), std::string::npos);
  std::vector<std::int16_t> even{2, 1, 1, 1};
  std::vector<std::byte> out(1);
  EXPECT_THROW(pack_levels(even, parse_sample_format("packed2").packed, out), std::invalid_argument);
  EXPECT_THROW(bytes_per_sample(parse_sample_format("packed2")), std::logic_error);
}

}  // namespace
}  // namespace deepnav
