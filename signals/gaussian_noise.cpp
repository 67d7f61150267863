#include "signals/gaussian_noise.hpp"

#include <cmath>

namespace deepnav {
namespace {

constexpr int kLayers = 256;
// Marsaglia & Tsang (2000), 256 layers: right edge of the base layer and common layer area
// for the unnormalised density f(x) = exp(-x^2/2).
constexpr double kR = 3.6541528853610088;
constexpr double kV = 4.92867323399e-3;
constexpr double kTwoPowMinus53 = 1.0 / 9007199254740992.0;

double density(double x) { return std::exp(-0.5 * x * x); }

/// x[i]: right edge of layer i (x[0] is the base layer's virtual width v/f(r), so that
/// the tail shares its layer); f[i] = density(x[i]); x[256] = 0.
struct ZigguratTables {
  std::array<double, kLayers + 1> x{};
  std::array<double, kLayers + 1> f{};
  ZigguratTables() {
    x[0] = kV / density(kR);
    x[1] = kR;
    for (int i = 1; i < kLayers - 1; ++i) x[i + 1] = std::sqrt(-2.0 * std::log(kV / x[i] + density(x[i])));
    x[kLayers] = 0.0;
    for (int i = 0; i <= kLayers; ++i) f[i] = density(x[i]);
    f[0] = density(kR);  // the base layer's ceiling is f(r)
  }
};

const ZigguratTables& tables() {
  static const ZigguratTables t;
  return t;
}

double uniform53(std::uint64_t bits) { return static_cast<double>(bits >> 11) * kTwoPowMinus53; }

}  // namespace

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

Xoshiro256ss::Xoshiro256ss(std::uint64_t seed) {
  std::uint64_t z = seed;
  for (auto& word : s_) {
    z = splitmix64(z);
    word = z;
  }
}

GaussianNoise::GaussianNoise(std::uint64_t seed) : rng_(seed) {}

// Layer index from bits 0-7, sign from bit 8, abscissa from bits 11-63: disjoint fields.
double GaussianNoise::slow_path(std::uint64_t bits) {
  const ZigguratTables& t = tables();
  for (;;) {
    const int i = static_cast<int>(bits & 0xFF);
    const double sign = (bits & 0x100) ? -1.0 : 1.0;
    const double x = uniform53(bits) * t.x[i];
    if (x < t.x[i + 1]) return sign * x;
    if (i == 0) {
      // Tail beyond r (Marsaglia 1964): x = r + E1/r accepted when 2 E2 > (E1/r)^2.
      double xt, y;
      do {
        xt = -std::log(uniform53(rng_()) + kTwoPowMinus53) / kR;
        y = -std::log(uniform53(rng_()) + kTwoPowMinus53);
      } while (y + y < xt * xt);
      return sign * (kR + xt);
    }
    const double y = t.f[i] + uniform53(rng_()) * (t.f[i + 1] - t.f[i]);
    if (y < density(x)) return sign * x;
    bits = rng_();
  }
}

double GaussianNoise::next() {
  const ZigguratTables& t = tables();
  const std::uint64_t bits = rng_();
  const int i = static_cast<int>(bits & 0xFF);
  const double x = uniform53(bits) * t.x[i];
  if (x < t.x[i + 1]) return (bits & 0x100) ? -x : x;
  return slow_path(bits);
}

template <bool kAdd>
void GaussianNoise::generate(float* out, std::size_t count, float sigma) {
  const ZigguratTables& t = tables();
  const double* x_edge = t.x.data();
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint64_t bits = rng_();
    const int i = static_cast<int>(bits & 0xFF);
    double x = uniform53(bits) * x_edge[i];
    if (x < x_edge[i + 1]) [[likely]] {
      if (bits & 0x100) x = -x;
    } else {
      x = slow_path(bits);
    }
    const float v = sigma * static_cast<float>(x);
    if constexpr (kAdd)
      out[k] += v;
    else
      out[k] = v;
  }
}

void GaussianNoise::fill_real(std::span<float> out, float sigma) { generate<false>(out.data(), out.size(), sigma); }
void GaussianNoise::add_real(std::span<float> out, float sigma) { generate<true>(out.data(), out.size(), sigma); }

// std::complex<float> is layout-compatible with float[2] (I, Q), so a complex block is
// filled as 2n interleaved floats: I from the even draw, Q from the odd one.
void GaussianNoise::fill_complex(std::span<std::complex<float>> out, float sigma_per_component) {
  generate<false>(reinterpret_cast<float*>(out.data()), 2 * out.size(), sigma_per_component);
}
void GaussianNoise::add_complex(std::span<std::complex<float>> out, float sigma_per_component) {
  generate<true>(reinterpret_cast<float*>(out.data()), 2 * out.size(), sigma_per_component);
}

double thermal_noise_sigma(double sample_rate_hz) { return std::sqrt(0.5 * sample_rate_hz); }

}  // namespace deepnav
