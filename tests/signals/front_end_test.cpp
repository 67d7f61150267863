#include "signals/sim/front_end.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <vector>

#include "signals/sim/if_file_writer.hpp"
#include "signals/sim/tone_generator.hpp"

namespace deepnav {
namespace {

constexpr double kFs = 4.092e6;
using Block = std::vector<std::complex<float>>;

FrontEndConfig config(SampleFormat format, int bits) {
  FrontEndConfig c;
  c.sample_rate_hz = kFs;
  c.if_hz = 0.0;
  c.format = format;
  c.adc.bits = bits;
  return c;
}

/// Runs the front end over a copy of the input and decodes the output to level units.
std::vector<float> digitize(FrontEnd& fe, Block input, std::int64_t first = 0) {
  std::vector<std::byte> bytes;
  fe.process(input, first, bytes);
  const std::size_t values = input.size() * (is_complex(fe.config().format) ? 2 : 1);
  std::vector<float> levels(values);
  unpack_levels(bytes.data(), values, fe.config().adc.bits, fe.config().format, levels.data());
  return levels;
}

Block tone(double amplitude, double freq_hz, std::size_t n) {
  Block x(n);
  ToneGenerator(freq_hz, kFs).generate(x, 0, static_cast<float>(amplitude));
  return x;
}

TEST(FrontEnd, BitsGiveTheOddLevelSet) {
  for (int bits : {1, 2, 3, 4}) {
    FrontEnd fe(config(SampleFormat::ibyte, bits), 1);
    const auto levels = digitize(fe, Block(100000));  // thermal noise alone
    std::set<float> seen(levels.begin(), levels.end()), expected;
    for (int l = 1; l < (1 << bits); l += 2) expected.insert({float(l), float(-l)});
    EXPECT_EQ(seen, expected) << bits << " bits";
  }
  // Full-width 8-bit ADC: two's-complement codes, reaching both ends under overload.
  AdcConfig adc;
  adc.bits = 8;
  adc.agc_enabled = false;
  adc.fixed_gain = 1.0;
  FrontEndConfig c = config(SampleFormat::ibyte, 8);
  c.adc = adc;
  c.thermal_noise = false;
  FrontEnd fe(c, 1);
  Block x = {{1e6f, -1e6f}, {0.5f, -0.5f}, {2.5f, -2.5f}};
  std::vector<std::byte> bytes;
  fe.process(x, 0, bytes);
  const std::vector<std::int8_t> expected = {127, -128, 0, -1, 1, -2};
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(static_cast<std::int8_t>(bytes[k]), expected[k]) << k;
}

TEST(FrontEnd, QuantizerSaturatesAndKeepsSign) {
  FrontEndConfig c = config(SampleFormat::ishort, 3);
  c.adc.agc_enabled = false;
  c.adc.fixed_gain = 1.0;
  c.thermal_noise = false;
  FrontEnd fe(c, 1);
  const Block x = {{100.0f, -100.0f}, {0.1f, -0.1f}, {2.1f, -2.1f}, {5.9f, 6.1f}};
  const auto levels = digitize(fe, x);
  const std::vector<float> expected = {7, -7, 1, -1, 3, -3, 5, 7};
  EXPECT_EQ(levels, expected);
}

TEST(FrontEnd, AgcSettlesAtTheOptimumLoading) {
  FrontEndConfig c = config(SampleFormat::ibyte, 2);
  c.adc.agc_time_constant_s = 0.5e-3;
  FrontEnd fe(c, 3);
  Block x(4092);
  for (int ms = 0; ms < 10; ++ms) digitize(fe, x, ms * 4092);
  const double noise_power_per_component = kFs / 2;
  EXPECT_NEAR(fe.agc().power_estimate() / noise_power_per_component, 1.0, 0.03);
  EXPECT_NEAR(fe.agc().gain() * std::sqrt(noise_power_per_component), 2.0 / 0.9957, 0.03);
  EXPECT_NEAR(optimum_quantizer_rms(1), 2.0 / 1.596, 1e-12);
}

TEST(FrontEnd, AgcFollowsAPowerStepWithItsTimeConstant) {
  FrontEndConfig c = config(SampleFormat::ibyte, 2);
  c.adc.agc_time_constant_s = 1e-3;
  c.thermal_noise = false;
  FrontEnd fe(c, 3);
  const double a1 = 10.0, a2 = 100.0;  // constant-envelope tone: power per component a^2/2
  const std::size_t step = 64 * 100;
  digitize(fe, tone(a1, 100e3, step), 0);
  const double p1 = a1 * a1 / 2, p2 = a2 * a2 / 2;
  EXPECT_NEAR(fe.agc().power_estimate() / p1, 1.0, 1e-3);
  const auto tau = static_cast<std::int64_t>(std::lround(1e-3 * kFs / 64) * 64);  // 4096 samples
  Block loud = tone(a2, 100e3, static_cast<std::size_t>(3 * tau));
  digitize(fe, Block(loud.begin(), loud.begin() + tau), step);
  EXPECT_NEAR((fe.agc().power_estimate() - p2) / (p1 - p2), std::exp(-1.0), 0.01);
  digitize(fe, Block(loud.begin() + tau, loud.end()), step + tau);
  EXPECT_NEAR((fe.agc().power_estimate() - p2) / (p1 - p2), std::exp(-3.0), 0.005);
}

/// Post-correlation SNR of a known complex tone: |mean amplitude|^2 over the residual
/// variance per sample (values interleaved I/Q).
double tone_snr(const std::vector<float>& y, double freq_hz) {
  const std::size_t n = y.size() / 2;
  ToneGenerator ref(-freq_hz, kFs);
  Block s(n, {1.0f, 0.0f});
  ref.mix(s, 0);
  std::complex<double> mu = 0;
  double power = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::complex<double> v(y[2 * k], y[2 * k + 1]);
    mu += v * std::complex<double>(s[k]);
    power += std::norm(v);
  }
  mu /= static_cast<double>(n);
  return std::norm(mu) / (power / static_cast<double>(n) - std::norm(mu));
}

double quantization_loss_db(int bits) {
  const double snr_per_sample = std::pow(10.0, -1.5);
  const double amplitude = std::sqrt(snr_per_sample * kFs);
  const Block x = tone(amplitude, 123e3, 1 << 22);
  FrontEnd ideal(config(SampleFormat::gr_complex, 0), 77);
  FrontEnd adc(config(SampleFormat::ibyte, bits), 77);  // same seed: same noise
  return 10 * std::log10(tone_snr(digitize(ideal, x), 123e3) / tone_snr(digitize(adc, x), 123e3));
}

TEST(FrontEnd, OneBitLossIsTwoOverPi) {
  const double loss = quantization_loss_db(1);
  RecordProperty("loss_db", std::to_string(loss));
  EXPECT_NEAR(loss, 1.96, 0.15);
}

TEST(FrontEnd, TwoBitLossAtOptimumLoadingIsAboutHalfADecibel) {
  const double loss = quantization_loss_db(2);
  RecordProperty("loss_db", std::to_string(loss));
  EXPECT_NEAR(loss, 0.55, 0.15);
}

/// SNR from the scatter of 1 ms coherent integrations of the known tone.
double integration_snr_db(const std::vector<float>& y, double freq_hz) {
  const std::size_t n = y.size() / 2, len = 4092;
  Block s(n, {1.0f, 0.0f});
  ToneGenerator(-freq_hz, kFs).mix(s, 0);
  std::vector<std::complex<double>> sums;
  for (std::size_t k0 = 0; k0 + len <= n; k0 += len) {
    std::complex<double> acc = 0;
    for (std::size_t k = k0; k < k0 + len; ++k)
      acc += std::complex<double>(y[2 * k], y[2 * k + 1]) * std::complex<double>(s[k]);
    sums.push_back(acc);
  }
  std::complex<double> mean = 0;
  for (auto v : sums) mean += v / static_cast<double>(sums.size());
  double var = 0;
  for (auto v : sums) var += std::norm(v - mean) / static_cast<double>(sums.size() - 1);
  return 10 * std::log10(std::norm(mean) / var);
}

TEST(FrontEnd, StrongCwJammerCapturesTheTwoBitAdc) {
  const double cn0 = 51.0;
  const Block x = tone(std::sqrt(std::pow(10.0, cn0 / 10)), 0.0, 4092 * 300);
  FrontEndConfig c = config(SampleFormat::ibyte, 2);
  c.cn0_ref_dbhz = cn0;
  FrontEnd clean(c, 9);
  const double snr_clean = integration_snr_db(digitize(clean, x), 0.0);
  JammerConfig cw;
  cw.type = JammerType::cw;
  cw.js_db = 45.0;  // J/N0 = 96 dB-Hz: 30 dB above the noise power in 4.092 MHz
  cw.center_offset_hz = 300e3;
  c.jammers = {cw};
  FrontEnd jammed(c, 9);
  const auto levels = digitize(jammed, x);
  std::size_t outer = 0;
  for (float v : levels) outer += std::abs(v) == 3.0f;
  EXPECT_GT(static_cast<double>(outer) / levels.size(), 0.3);  // the CW drives the outer levels
  const double snr_jammed = integration_snr_db(levels, 0.0);
  RecordProperty("snr_clean_db", std::to_string(snr_clean));
  RecordProperty("snr_jammed_db", std::to_string(snr_jammed));
  // 1 ms at 51 dB-Hz: 21 dB less the 2-bit loss; the jammer costs several dB more.
  EXPECT_NEAR(snr_clean, 21.0 - 0.55, 1.0);
  EXPECT_LT(snr_jammed, snr_clean - 3.0);
}

TEST(FrontEnd, OutputDoesNotDependOnBlockBoundaries) {
  FrontEndConfig c = config(SampleFormat::ibyte, 2);
  JammerConfig pulsed;
  pulsed.type = JammerType::pulsed;
  pulsed.js_db = 40;
  pulsed.duty_cycle = 0.2;
  pulsed.pulse_rate_hz = 2000;
  pulsed.bandwidth_hz = 1e6;
  c.jammers = {pulsed};
  const Block x = tone(300.0, 50e3, 20000);
  FrontEnd one(c, 5), many(c, 5);
  std::vector<std::byte> whole, part, pieces;
  Block copy = x;
  one.process(copy, 1000, whole);
  const std::size_t cuts[] = {0, 63, 64, 1000, 4093, 20000};
  for (int k = 0; k + 1 < 6; ++k) {
    Block piece(x.begin() + cuts[k], x.begin() + cuts[k + 1]);
    many.process(piece, 1000 + static_cast<std::int64_t>(cuts[k]), part);
    pieces.insert(pieces.end(), part.begin(), part.end());
  }
  EXPECT_EQ(whole, pieces);
}

TEST(FrontEnd, OutputDoesNotDependOnTheNoiseThreads) {
  // The thermal noise is split across workers at its generator's chunks (32768 complex or
  // 65536 real samples); blocks that start and end inside chunks, real and complex.
  for (const SampleFormat format : {SampleFormat::ibyte, SampleFormat::byte}) {
    const FrontEndConfig c = config(format, 2);
    FrontEnd one(c, 9, 1), three(c, 9, 3);
    std::int64_t first = 30000;
    for (const std::size_t n : {std::size_t{100000}, std::size_t{7}, std::size_t{150001}, std::size_t{70000}}) {
      const Block x = tone(300.0, 50e3, n);
      std::vector<std::byte> a, b;
      Block copy_a = x, copy_b = x;
      one.process(copy_a, first, a);
      three.process(copy_b, first, b);
      EXPECT_EQ(a, b) << to_string(format) << " block of " << n << " samples at " << first;
      first += static_cast<std::int64_t>(n);
    }
  }
}

TEST(FrontEnd, EveryFormatRoundTripsThroughItsBytes) {
  const Block x = {{1.25f, -3.5f}, {0.0f, 7.75f}, {-100.0f, 2.0f}};
  for (SampleFormat format :
       {SampleFormat::ibyte, SampleFormat::ishort, SampleFormat::gr_complex, SampleFormat::byte, SampleFormat::cu8}) {
    const int bits = format == SampleFormat::gr_complex ? 0 : format == SampleFormat::ishort ? 12 : 4;
    FrontEndConfig c = config(format, bits);
    c.adc.agc_enabled = false;
    c.adc.fixed_gain = 2.0;
    c.thermal_noise = false;
    FrontEnd fe(c, 1);
    Block in = x;
    std::vector<std::byte> bytes;
    fe.process(in, 0, bytes);
    ASSERT_EQ(bytes.size(), x.size() * bytes_per_sample(format));
    std::vector<float> values(is_complex(format) ? 2 * x.size() : x.size());
    unpack_levels(bytes.data(), values.size(), bits, format, values.data());
    for (std::size_t k = 0; k < values.size(); ++k) {
      const float component =
          is_complex(format) ? (k % 2 ? x[k / 2].imag() : x[k / 2].real()) : std::sqrt(2.0f) * x[k].real();
      const float y = 2.0f * component;
      const float max_level = std::ldexp(1.0f, bits) - 1.0f;
      const float expected = bits == 0 ? y : std::clamp(2.0f * std::floor(y / 2.0f) + 1.0f, -max_level, max_level);
      EXPECT_EQ(values[k], expected) << to_string(format) << " value " << k;
    }
    // Through a file and back.
    const auto path =
        std::filesystem::temp_directory_path() / ("deepnav_fe_" + std::string(to_string(format)) + ".bin");
    {
      IfFileWriter writer(path);
      writer.write(bytes);
      writer.finish();
    }
    std::ifstream in_file(path, std::ios::binary);
    std::vector<char> back((std::istreambuf_iterator<char>(in_file)), std::istreambuf_iterator<char>());
    ASSERT_EQ(back.size(), bytes.size());
    EXPECT_EQ(std::memcmp(back.data(), bytes.data(), bytes.size()), 0);
    std::filesystem::remove(path);
  }
}

TEST(FrontEnd, PackedFormatsHoldTheQuantizerLevelsInTimeOrder) {
  Block x(32);
  for (std::size_t k = 0; k < x.size(); ++k)
    x[k] = {static_cast<float>(k % 7) - 3.3f, 2.6f - static_cast<float>(k % 5) * 1.1f};
  for (const char* name :
       {"packed2_iq", "packed4", "packed1_qi_msb", "packed2_sm_bytemsb_w16be", "packed4_iq_ob_w32le"}) {
    const SampleFormat format = parse_sample_format(name);
    const int bits = format.packed.bits;
    FrontEndConfig c = config(format, bits);
    c.adc.agc_enabled = false;
    c.adc.fixed_gain = 2.0;
    c.thermal_noise = false;
    FrontEnd fe(c, 1);
    Block in = x;
    std::vector<std::byte> bytes;
    fe.process(in, 0, bytes);
    ASSERT_EQ(bytes.size(), x.size() / samples_per_word(format) * bytes_per_word(format)) << name;
    std::vector<float> values(is_complex(format) ? 2 * x.size() : x.size());
    unpack_levels(bytes.data(), values.size(), bits, format, values.data());
    for (std::size_t k = 0; k < values.size(); ++k) {
      // In time order: I, Q of each sample (the unpacked values of a qi layout come Q first).
      const bool complex = is_complex(format);
      const std::size_t sample = complex ? k / 2 : k;
      const bool q = complex && ((k % 2 == 1) != format.packed.q_first);
      const float component = complex ? (q ? x[sample].imag() : x[sample].real()) : std::sqrt(2.0f) * x[sample].real();
      const float y = 2.0f * component;
      const float max_level = std::ldexp(1.0f, bits) - 1.0f;
      EXPECT_EQ(values[k], std::clamp(2.0f * std::floor(y / 2.0f) + 1.0f, -max_level, max_level))
          << name << " value " << k;
    }
  }
  Block odd(3);
  std::vector<std::byte> bytes;
  FrontEnd fe(config(parse_sample_format("packed2"), 2), 1);
  EXPECT_THROW(fe.process(odd, 0, bytes), std::logic_error);  // 3 samples are not whole bytes of 4
}

TEST(FrontEnd, Cu8StoresEightBitLevelsAroundTheMidpoint) {
  // An 8-bit ADC in cu8 fills 0..255 (level L stored as (L + 255) / 2); four bits sit in the
  // middle of the range, 120..135.
  for (const int bits : {8, 4}) {
    FrontEndConfig c = config(SampleFormat::cu8, bits);
    c.adc.agc_enabled = false;
    c.adc.fixed_gain = 1.0;
    c.thermal_noise = false;
    FrontEnd fe(c, 1);
    Block x = {{-1000.0f, 1000.0f}, {0.4f, -0.4f}, {3.0f, -3.0f}};
    std::vector<std::byte> bytes;
    fe.process(x, 0, bytes);
    ASSERT_EQ(bytes.size(), 6u);
    const int top = (1 << (bits - 1)) + 127, bottom = 128 - (1 << (bits - 1));
    EXPECT_EQ(std::to_integer<int>(bytes[0]), bottom) << bits;
    EXPECT_EQ(std::to_integer<int>(bytes[1]), top) << bits;
    EXPECT_EQ(std::to_integer<int>(bytes[2]), 128) << bits;  // level +1
    EXPECT_EQ(std::to_integer<int>(bytes[3]), 127) << bits;  // level -1
    EXPECT_EQ(std::to_integer<int>(bytes[4]), 129) << bits;  // level +3
    EXPECT_EQ(std::to_integer<int>(bytes[5]), 126) << bits;  // level -3
  }
}

TEST(IfFileWriter, PartialFileOnlyBecomesTheFileOnFinish) {
  const auto path = std::filesystem::temp_directory_path() / "deepnav_writer_test.bin";
  std::filesystem::remove(path);
  const std::vector<std::byte> data(1000, std::byte{0x5A});
  {
    IfFileWriter writer(path);
    writer.write(data);
    EXPECT_TRUE(std::filesystem::exists(writer.partial_path()));
    EXPECT_FALSE(std::filesystem::exists(path));
    writer.finish();
    EXPECT_FALSE(std::filesystem::exists(writer.partial_path()));
    EXPECT_EQ(writer.bytes_written(), 1000u);
  }
  EXPECT_EQ(std::filesystem::file_size(path), 1000u);
  std::filesystem::remove(path);
  std::filesystem::path partial;
  {
    IfFileWriter abandoned(path);
    abandoned.write(data);
    partial = abandoned.partial_path();
  }
  EXPECT_FALSE(std::filesystem::exists(partial));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(IfFileWriter, UnwritablePathIsNamed) {
  const std::string path = "/nonexistent_deepnav_dir/out.bin";
  try {
    IfFileWriter writer(path);
    FAIL() << "opened " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(FrontEnd, BadSettingsNameTheField) {
  auto message = [](const FrontEndConfig& c) {
    try {
      FrontEnd fe(c, 1);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(config(SampleFormat::ibyte, 9)).find("adc.bits"), std::string::npos);
  EXPECT_NE(message(config(SampleFormat::ibyte, 0)).find("adc.bits"), std::string::npos);
  EXPECT_NE(message(config(SampleFormat::ishort, 17)).find("adc.bits"), std::string::npos);
  FrontEndConfig c = config(SampleFormat::ibyte, 2);
  c.adc.agc_time_constant_s = 0.0;
  EXPECT_NE(message(c).find("adc.agc_time_constant_s"), std::string::npos);
  c = config(SampleFormat::ibyte, 2);
  c.jammers.resize(2);
  c.jammers[1].js_db = 500;
  const std::string m = message(c);
  EXPECT_NE(m.find("jammers[1]"), std::string::npos) << m;
  EXPECT_NE(m.find("js_db"), std::string::npos) << m;
}

}  // namespace
}  // namespace deepnav
