// Raw IF bytes -> samples (receiver/sources/sample_converter.hpp): regressions found by fuzzing
// (tests/fuzz/sample_converter_fuzzer.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "receiver/sources/sample_converter.hpp"

namespace deepnav {
namespace {

std::vector<std::byte> floats(std::initializer_list<std::uint32_t> bits) {
  std::vector<std::byte> out(bits.size() * 4);
  std::size_t at = 0;
  for (std::uint32_t b : bits) std::memcpy(out.data() + 4 * at++, &b, 4);
  return out;
}

// A gr_complex start made of subnormal floats has an RMS so small that the scale to 2048
// overflows a float; the infinite scale turned the zero sample after it into NaN (0 x inf)
// and its conversion to int16 was undefined (the fuzzer's input, verbatim).
TEST(SampleConverter, SubnormalGrComplexStartKeepsAFiniteScale) {
  const std::vector<std::byte> raw = floats({0x0043fee1u, 0x00130400u, 0x0002057eu, 0x00000000u});
  SampleConverter converter(SampleFormat::gr_complex, false);
  converter.calibrate(raw);
  EXPECT_TRUE(std::isfinite(converter.float_scale()));
  std::array<Sample, 2> out{};
  converter.convert(raw, out, 0);
  EXPECT_EQ(out[1], Sample(0, 0));
  EXPECT_EQ(out[0], Sample(0, 0));  // unit scale: subnormal values round to zero
}

TEST(SampleConverter, GrComplexScalesTheStartToRms2048) {
  const float one = 1.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &one, 4);
  const std::vector<std::byte> raw = floats({bits, bits, bits, bits});
  SampleConverter converter(SampleFormat::gr_complex, false);
  converter.calibrate(raw);
  std::array<Sample, 2> out{};
  converter.convert(raw, out, 0);
  // RMS of |I + jQ| is sqrt(2) here: each component lands at 2048 / sqrt(2).
  EXPECT_EQ(out[0], Sample(1448, 1448));
}

}  // namespace
}  // namespace deepnav
