#include "signals/sim/gaussian_noise.hpp"

#include <bit>

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

const std::array<float, kLayers + 1>& float_edges() {
  static const std::array<float, kLayers + 1> edges = [] {
    std::array<float, kLayers + 1> e{};
    for (int i = 0; i <= kLayers; ++i) e[i] = static_cast<float>(tables().x[i]);
    return e;
  }();
  return edges;
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

// Tail beyond r (Marsaglia 1964): x = r + E1/r accepted when 2 E2 > (E1/r)^2.
double GaussianNoise::tail() {
  double xt, y;
  do {
    xt = -std::log(uniform53(rng_()) + kTwoPowMinus53) / kR;
    y = -std::log(uniform53(rng_()) + kTwoPowMinus53);
  } while (y + y < xt * xt);
  return kR + xt;
}

// Layer index from bits 0-7, sign from bit 8, abscissa from bits 11-63: disjoint fields.
double GaussianNoise::slow_path(std::uint64_t bits) {
  const ZigguratTables& t = tables();
  for (;;) {
    const int i = static_cast<int>(bits & 0xFF);
    const double sign = (bits & 0x100) ? -1.0 : 1.0;
    const double x = uniform53(bits) * t.x[i];
    if (x < t.x[i + 1]) return sign * x;
    if (i == 0) {
      return sign * tail();
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

// Block fill: each 64-bit word feeds two draws, one from each 32-bit half (layer in bits
// 0-7, sign in bit 8, a 23-bit uniform in bits 9-31 -- float resolution, disjoint fields).
// A draw that misses its layer's core finishes the ziggurat for that same point (tail or
// wedge test); a wedge rejection restarts with the full 64-bit sampler, which is itself
// exact, so the result is N(0, 1) either way.
double GaussianNoise::finish_half(std::uint32_t half) {
  const ZigguratTables& t = tables();
  const int i = static_cast<int>(half & 0xFF);
  const double sign = (half & 0x100) ? -1.0 : 1.0;
  const double x = static_cast<double>(half >> 9) * (1.0 / 8388608.0) * t.x[i];
  if (x < t.x[i + 1]) return sign * x;
  if (i == 0) {
    return sign * tail();
  }
  const double y = t.f[i] + uniform53(rng_()) * (t.f[i + 1] - t.f[i]);
  if (y < density(x)) return sign * x;
  return next();
}

template <bool kAdd>
void GaussianNoise::generate(float* out, std::size_t count, float sigma) {
  const float* x_edge = float_edges().data();
  auto draw = [&](std::uint32_t half) {
    const int i = static_cast<int>(half & 0xFF);
    float x = static_cast<float>(static_cast<std::int32_t>(half >> 9)) * (1.0f / 8388608.0f) * x_edge[i];
    if (x < x_edge[i + 1]) [[likely]]  // sign from bit 8 by flipping the float's sign bit: no branch to mispredict
      return std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) ^ ((half & 0x100u) << 23));
    return static_cast<float>(finish_half(half));
  };
  auto put = [&](std::size_t k, float v) {
    if constexpr (kAdd) out[k] += sigma * v;
    else out[k] = sigma * v;
  };
  // A half word left over by the previous call is used first, so the draw sequence does
  // not depend on how the stream is cut into calls.
  std::size_t k = 0;
  if (has_pending_ && count > 0) {
    put(k++, draw(pending_));
    has_pending_ = false;
  }
  for (; k + 2 <= count; k += 2) {
    const std::uint64_t bits = rng_();
    put(k, draw(static_cast<std::uint32_t>(bits)));
    put(k + 1, draw(static_cast<std::uint32_t>(bits >> 32)));
  }
  if (k < count) {
    const std::uint64_t bits = rng_();
    put(k, draw(static_cast<std::uint32_t>(bits)));
    pending_ = static_cast<std::uint32_t>(bits >> 32);
    has_pending_ = true;
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
