#pragma once
// Samples as the converters the correlator tests cover give them: one signal sample plus
// Gaussian noise, quantized to 1 bit, 2 bits, or rounded to 8, 12 or full-scale 16 bits.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "receiver/sources/sample_source.hpp"

namespace deepnav::test_input {

enum class Converter { one_bit, two_bits, eight_bits, twelve_bits, sixteen_bits };
inline constexpr int kConverters = 5;

/// The signal amplitude each converter's tests use (its full scale's share).
inline double converter_amplitude(Converter c) {
  constexpr double amp[] = {1.0, 1.0, 20.0, 300.0, 6000.0};
  return amp[static_cast<int>(c)];
}

/// The sample of signal (i, q), which carries converter_amplitude(c), with noise.
inline Sample converter_sample(Converter c, double i, double q, std::mt19937_64& rng) {
  constexpr double sigma[] = {0.0, 1.5, 30.0, 500.0, 9000.0};
  std::normal_distribution<double> noise(0.0, 1.0);
  if (c == Converter::one_bit) {  // signs of signal plus noise
    i = i + 2.0 * noise(rng) >= 0.0 ? 1.0 : -1.0;
    q = q + 2.0 * noise(rng) >= 0.0 ? 1.0 : -1.0;
  } else if (c == Converter::two_bits) {  // +-1, +-3
    const auto two = [](double v) { return v >= 0.0 ? (v > 2.0 ? 3.0 : 1.0) : (v < -2.0 ? -3.0 : -1.0); };
    i = two(i + sigma[1] * noise(rng));
    q = two(q + sigma[1] * noise(rng));
  } else {
    i += sigma[static_cast<int>(c)] * noise(rng);
    q += sigma[static_cast<int>(c)] * noise(rng);
  }
  const auto clamp16 = [](double v) { return static_cast<std::int16_t>(std::clamp(std::lround(v), -32768L, 32767L)); };
  return {clamp16(i), clamp16(q)};
}

}  // namespace deepnav::test_input
