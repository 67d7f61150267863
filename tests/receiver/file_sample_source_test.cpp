#include "receiver/sources/file_sample_source.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace deepnav {
namespace {

std::filesystem::path write_file(const std::string& name, const void* data, std::size_t bytes) {
  const auto dir = std::filesystem::temp_directory_path() / "deepnav_file_sample_source";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  return path;
}

std::vector<Sample> read_all(FileSampleSource& source, std::size_t block = 3) {
  std::vector<Sample> all;
  SampleBlock b;
  while (source.read_block(b, block)) {
    EXPECT_EQ(b.first_sample_index, source.next_sample_index() - static_cast<std::int64_t>(b.samples.size()));
    all.insert(all.end(), b.samples.begin(), b.samples.end());
  }
  EXPECT_TRUE(source.at_end());
  return all;
}

FileSampleSourceOptions options(const std::filesystem::path& path, SampleFormat format) {
  FileSampleSourceOptions o;
  o.path = path;
  o.format = format;
  o.sample_rate_hz = 1000.0;
  return o;
}

TEST(FileSampleSource, ReadsIbyte) {
  const std::int8_t data[] = {1, -1, 3, -3, -128, 127, 0, 2};
  FileSampleSource source(options(write_file("ibyte.bin", data, sizeof data), SampleFormat::ibyte));
  EXPECT_EQ(source.total_samples(), 4);
  EXPECT_FALSE(source.is_real());
  const auto s = read_all(source);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0], Sample(1, -1));
  EXPECT_EQ(s[1], Sample(3, -3));
  EXPECT_EQ(s[2], Sample(-128, 127));
  EXPECT_EQ(s[3], Sample(0, 2));
  EXPECT_TRUE(source.warnings().empty());
}

TEST(FileSampleSource, ReadsCu8AsOddLevelsAroundTheMidpoint) {
  // u - 127.5 in half units: 0 -> -255, 255 -> +255, 127 -> -1, 128 -> +1.
  const std::uint8_t data[] = {0, 255, 127, 128, 128, 127, 200, 3};
  auto o = options(write_file("cu8.bin", data, sizeof data), SampleFormat::cu8);
  {
    FileSampleSource source(o);
    EXPECT_EQ(source.total_samples(), 4);
    EXPECT_FALSE(source.is_real());
    const auto s = read_all(source);
    ASSERT_EQ(s.size(), 4u);
    EXPECT_EQ(s[0], Sample(-255, 255));
    EXPECT_EQ(s[1], Sample(-1, 1));
    EXPECT_EQ(s[2], Sample(1, -1));
    EXPECT_EQ(s[3], Sample(145, -249));
  }
  o.inverted_spectrum = true;
  FileSampleSource inverted(o);
  const auto s = read_all(inverted);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0], Sample(-255, -255));
  EXPECT_EQ(s[3], Sample(145, 249));
}

TEST(FileSampleSource, ReadsPackedWordsInPiecesAndSkipsIntoAWord) {
  // two_bit_packed, 4 real samples a byte from bits 1..0 up: 0xE4 is +1 +3 -3 -1.
  const std::uint8_t data[] = {0xE4, 0x1B, 0xE4};
  auto o = options(write_file("packed2.bin", data, sizeof data), parse_sample_format("two_bit_packed"));
  {
    FileSampleSource source(o);
    EXPECT_EQ(source.total_samples(), 12);
    EXPECT_TRUE(source.is_real());
    const auto s = read_all(source, 3);  // blocks shorter than a word
    ASSERT_EQ(s.size(), 12u);
    const int expected[] = {1, 3, -3, -1, -1, -3, 3, 1, 1, 3, -3, -1};
    for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(s[i], Sample(static_cast<std::int16_t>(expected[i]), 0)) << i;
  }
  o.skip_s = 0.006;  // sample 6, inside the second byte
  FileSampleSource skipped(o);
  EXPECT_EQ(skipped.next_sample_index(), 6);
  const auto s = read_all(skipped, 5);
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s[0], Sample(3, 0));
  EXPECT_EQ(s[1], Sample(1, 0));
  EXPECT_EQ(s[2], Sample(1, 0));
  // Complex, Q first, first value in the top bits, with the spectrum inverted: 0b01'10'11'00
  // is Q +3, I -3, then Q -1, I +1.
  const std::uint8_t cpx[] = {0b01101100};
  auto c = options(write_file("cpx.bin", cpx, sizeof cpx), parse_sample_format("two_bit_cpx"));
  c.inverted_spectrum = true;
  FileSampleSource complex_source(c);
  EXPECT_FALSE(complex_source.is_real());
  const auto z = read_all(complex_source, 1);
  ASSERT_EQ(z.size(), 2u);
  EXPECT_EQ(z[0], Sample(-3, -3));
  EXPECT_EQ(z[1], Sample(1, 1));
}

TEST(FileSampleSource, AReadAfterASkipIntoAWordGoesOnPastThatWord) {
  // packed2_iq_w32le: 8 I/Q samples in each 32-bit word. A skip of one sample left the first
  // read the 7 samples after it, too few to judge or acquire on (`run` looked at them alone).
  std::vector<std::uint8_t> data(64);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(37 * i + 11);
  auto o = options(write_file("packed_w32.bin", data.data(), data.size()), parse_sample_format("packed2_iq_w32le"));
  FileSampleSource whole(o);
  std::vector<Sample> reference(128);
  ASSERT_EQ(whole.read(reference), 128u);
  o.skip_s = 0.001;  // sample 1 at 1 kHz
  FileSampleSource skipped(o);
  std::vector<Sample> first(20);
  ASSERT_EQ(skipped.read(first), 15u) << "the 7 samples left in the word and the next whole word";
  EXPECT_TRUE(std::equal(first.begin(), first.begin() + 15, reference.begin() + 1));
  EXPECT_EQ(skipped.next_sample_index(), 16);
  std::vector<Sample> rest(200);
  ASSERT_EQ(skipped.read(rest), 112u);
  EXPECT_TRUE(std::equal(rest.begin(), rest.begin() + 112, reference.begin() + 16));
  EXPECT_EQ(skipped.read(rest), 0u);
  EXPECT_TRUE(skipped.at_end());
}

TEST(FileSampleSource, SkipsAHeaderAndFooterAndStopsAtTheAnnouncedLength) {
  // 3 header bytes, then ibyte samples (1,-1) (2,-2) (3,-3) (4,-4), then a 1-byte footer.
  const std::int8_t data[] = {9, 9, 9, 1, -1, 2, -2, 3, -3, 4, -4, 9};
  auto o = options(write_file("header.bin", data, sizeof data), SampleFormat::ibyte);
  o.header_bytes = 3;
  o.footer_bytes = 1;
  {
    FileSampleSource source(o);
    EXPECT_EQ(source.total_samples(), 4);
    const auto s = read_all(source);
    ASSERT_EQ(s.size(), 4u);
    EXPECT_EQ(s[0], Sample(1, -1));
    EXPECT_EQ(s[3], Sample(4, -4));
    EXPECT_TRUE(source.warnings().empty());
  }
  o.length_bytes = 4;  // two samples, as a block's cycles say
  o.skip_s = 0.001;
  FileSampleSource two(o);
  EXPECT_EQ(two.total_samples(), 2);
  const auto s = read_all(two);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0], Sample(2, -2));
  o.length_bytes = 100;  // more than there is: read what there is, and say so
  o.skip_s = 0.0;
  FileSampleSource longer(o);
  EXPECT_EQ(longer.total_samples(), 4);
  ASSERT_EQ(longer.warnings().size(), 1u);
  EXPECT_NE(longer.warnings()[0].find("100 bytes of samples were announced"), std::string::npos);
  o.header_bytes = 12;
  EXPECT_THROW(FileSampleSource{o}, std::runtime_error);
}

TEST(FileSampleSource, ReadsIshortAndInvertsSpectrumWithSaturation) {
  const std::int16_t data[] = {1000, -2000, -32768, -32768, 7, 32767};
  auto o = options(write_file("ishort.bin", data, sizeof data), SampleFormat::ishort);
  {
    FileSampleSource source(o);
    const auto s = read_all(source, 2);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s[0], Sample(1000, -2000));
    EXPECT_EQ(s[1], Sample(-32768, -32768));
    EXPECT_EQ(s[2], Sample(7, 32767));
  }
  o.inverted_spectrum = true;
  FileSampleSource source(o);
  const auto s = read_all(source, 2);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0], Sample(1000, 2000));
  EXPECT_EQ(s[1], Sample(-32768, 32767));
  EXPECT_EQ(s[2], Sample(7, -32767));
}

TEST(FileSampleSource, ReadsRealBytesWithZeroQ) {
  const std::int8_t data[] = {3, -1, 1, -3, 0};
  auto o = options(write_file("byte.bin", data, sizeof data), SampleFormat::byte);
  o.intermediate_frequency_hz = 250.0;
  FileSampleSource source(o);
  EXPECT_TRUE(source.is_real());
  EXPECT_DOUBLE_EQ(source.intermediate_frequency_hz(), 250.0);
  const auto s = read_all(source);
  ASSERT_EQ(s.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(s[i], Sample(data[i], 0));
}

TEST(FileSampleSource, ScalesGrComplexFromTheFirstBlockRms) {
  // The scale maps the RMS of the first block (outlier included) to 2048.
  std::vector<float> data;
  for (int i = 0; i < 1000; ++i) {
    const float sign = (i % 2 == 0) ? 1.0f : -1.0f;
    data.push_back(sign * 0.3f);
    data.push_back(-sign * 0.4f);
  }
  data.push_back(20.0f);  // an outlier saturates instead of wrapping
  data.push_back(-20.0f);
  const double rms = std::sqrt((1000 * 0.25 + 800.0) / 1001.0);
  FileSampleSource source(options(write_file("cf32.bin", data.data(), data.size() * 4), SampleFormat::gr_complex));
  EXPECT_NEAR(source.float_scale(), 2048.0 / rms, 0.01);
  const auto s = read_all(source, 4096);
  ASSERT_EQ(s.size(), 1001u);
  const float k = source.float_scale();
  EXPECT_EQ(s[0], Sample(static_cast<std::int16_t>(std::lround(0.3f * k)),
                         static_cast<std::int16_t>(std::lround(-0.4f * k))));
  EXPECT_EQ(s[1], Sample(static_cast<std::int16_t>(std::lround(-0.3f * k)),
                         static_cast<std::int16_t>(std::lround(0.4f * k))));
  EXPECT_EQ(s[1000], Sample(32767, -32768));
}

TEST(FileSampleSource, SkipKeepsAbsoluteIndex) {
  std::vector<std::int8_t> data;
  for (int i = 0; i < 100; ++i) {
    data.push_back(static_cast<std::int8_t>(i));
    data.push_back(static_cast<std::int8_t>(-i));
  }
  auto o = options(write_file("skip.bin", data.data(), data.size()), SampleFormat::ibyte);
  o.skip_s = 0.030;  // 30 samples at 1 kHz
  FileSampleSource source(o);
  EXPECT_EQ(source.next_sample_index(), 30);
  SampleBlock b;
  ASSERT_TRUE(source.read_block(b, 10));
  EXPECT_EQ(b.first_sample_index, 30);
  ASSERT_EQ(b.samples.size(), 10u);
  EXPECT_EQ(b.samples[0], Sample(30, -30));
  EXPECT_EQ(b.samples[9], Sample(39, -39));
  const auto rest = read_all(source, 64);
  EXPECT_EQ(rest.size(), 60u);
  EXPECT_EQ(rest.back(), Sample(99, -99));

  o.skip_s = 0.1;
  EXPECT_THROW(FileSampleSource{o}, std::runtime_error);
  o.skip_s = -1.0;
  EXPECT_THROW(FileSampleSource{o}, std::invalid_argument);
}

TEST(FileSampleSource, WarnsAboutTrailingPartialSample) {
  const std::int16_t data[] = {1, 2, 3, 4, 5};  // 10 bytes: two ishort samples and 2 stray bytes
  FileSampleSource source(options(write_file("partial.bin", data, sizeof data), SampleFormat::ishort));
  EXPECT_EQ(source.total_samples(), 2);
  ASSERT_EQ(source.warnings().size(), 1u);
  EXPECT_NE(source.warnings()[0].find("2 byte(s)"), std::string::npos) << source.warnings()[0];
  EXPECT_NE(source.warnings()[0].find("partial.bin"), std::string::npos);
  EXPECT_EQ(read_all(source).size(), 2u);
}

TEST(FileSampleSource, RejectsMissingEmptyAndTooShortFiles) {
  const auto missing = std::filesystem::temp_directory_path() / "deepnav_file_sample_source" / "no_such_file.bin";
  try {
    FileSampleSource source(options(missing, SampleFormat::ibyte));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_file.bin"), std::string::npos) << e.what();
  }
  const auto empty = write_file("empty.bin", "", 0);
  try {
    FileSampleSource source(options(empty, SampleFormat::byte));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
  const char three[] = {1, 2, 3};
  EXPECT_THROW(FileSampleSource(options(write_file("three.bin", three, 3), SampleFormat::ishort)), std::runtime_error);
  auto o = options(empty, SampleFormat::byte);
  o.sample_rate_hz = 0.0;
  EXPECT_THROW(FileSampleSource{o}, std::invalid_argument);
}

TEST(FileSampleSource, UnknownFormatNamesTheChoices) {
  try {
    (void)parse_sample_format("int4");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("int4"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("gr_complex"), std::string::npos);
  }
}

TEST(FileSampleSource, ReadsLargeFilesInBoundedChunks) {
  std::vector<std::int8_t> data(2 * 200000);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::int8_t>(i % 7);
  FileSampleSource source(options(write_file("large.bin", data.data(), data.size()), SampleFormat::ibyte));
  std::vector<Sample> buffer(300000);
  const std::size_t first = source.read(buffer);
  EXPECT_GT(first, 0u);
  EXPECT_LT(first, 200000u);  // one call never reads the whole file at once
  std::size_t total = first;
  while (const std::size_t n = source.read(buffer)) total += n;
  EXPECT_EQ(total, 200000u);
}

}  // namespace
}  // namespace deepnav
