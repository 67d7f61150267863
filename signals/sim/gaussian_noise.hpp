#pragma once
// Fast, seeded, deterministic Gaussian noise for filling sample blocks.
//
// Uniform bits come from xoshiro256** (Blackman & Vigna), seeded through
// splitmix64 so that nearby seeds give unrelated streams. Normals come from the
// Marsaglia-Tsang ziggurat with 256 layers, in the variant that takes the layer
// index, the sign and the 53-bit uniform from disjoint bits of one 64-bit word
// (Doornik 2005: reusing the same bits for layer and abscissa correlates them).
// The ziggurat is exact up to floating-point rounding: about 99% of draws are one
// multiply and one compare; the rest evaluate the wedge under exp(-x^2/2) or the
// |x| > 3.654 tail with Marsaglia's exponential method, so the tails are right
// out to the resolution of the uniforms (no table truncation). next() takes one 64-bit
// word per draw (53-bit uniform); the block fills take two draws per word, one per 32-bit
// half with a 23-bit uniform, which is the resolution of the float samples they produce.
//
// Noise power convention of the synthesizer (N0 = 1): complex baseband noise at
// sample rate fs has total variance N0*fs, i.e. sigma = sqrt(fs/2) per component;
// real IF noise has variance N0*fs/2, i.e. the same sigma = sqrt(fs/2).
#include <array>
#include <complex>
#include <cstdint>
#include <span>

namespace deepnav {

/// xoshiro256**: 256-bit state, period 2^256-1, passes BigCrush; about 1 ns per word.
class Xoshiro256ss {
 public:
  explicit Xoshiro256ss(std::uint64_t seed);
  std::uint64_t operator()() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_{};
};

/// One splitmix64 step: a bijective 64-bit mixer, used to derive seeds.
std::uint64_t splitmix64(std::uint64_t x);

/// Standard normal deviates from a seeded xoshiro256** stream.
class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed);

  /// One N(0, 1) draw.
  double next();

  /// out[k] = sigma * N(0,1) (fill) or out[k] += sigma * N(0,1) (add).
  void fill_real(std::span<float> out, float sigma);
  void add_real(std::span<float> out, float sigma);
  /// Each of I and Q gets an independent N(0, sigma_per_component^2) draw (I first);
  /// the complex variance is 2 sigma_per_component^2.
  void fill_complex(std::span<std::complex<float>> out, float sigma_per_component);
  void add_complex(std::span<std::complex<float>> out, float sigma_per_component);

 private:
  /// A draw from the normal tail beyond the base layer's edge r (positive).
  double tail();
  double slow_path(std::uint64_t bits);
  double finish_half(std::uint32_t half);
  template <bool kAdd>
  void generate(float* out, std::size_t count, float sigma);
  Xoshiro256ss rng_;
  std::uint32_t pending_ = 0;  ///< unused upper half of the last word of a block fill
  bool has_pending_ = false;
};

/// Per-component standard deviation of thermal noise with N0 = 1 at sample rate
/// fs: sqrt(fs/2), both for complex baseband (variance fs in all) and real IF
/// (variance fs/2).
double thermal_noise_sigma(double sample_rate_hz);

}  // namespace deepnav
