#pragma once
// Gaussian noise addressed by absolute sample index: the value added to sample n is a
// function of (seed, n) only, so a run gives the same samples whatever block sizes the
// caller uses, and a block may start anywhere (a jammer that switches on mid-run, a
// filter that needs history before the block).
//
// The draw sequence is cut into chunks of kChunkDraws normals; chunk c is the
// GaussianNoise stream seeded with a hash of (seed, c). Contiguous requests continue
// the current stream at no extra cost; a jump reseeds the chunk and skips to the
// position (at most one chunk of draws).
#include <complex>
#include <cstdint>
#include <span>

#include "signals/sim/gaussian_noise.hpp"

namespace deepnav {

class IndexedNoise {
 public:
  static constexpr std::int64_t kChunkDraws = 1 << 16;

  explicit IndexedNoise(std::uint64_t seed);

  /// out[k] += sigma * N(0,1) for the real samples first_sample + k (one draw per sample).
  void add_real(std::span<float> out, std::int64_t first_sample, float sigma);
  void fill_real(std::span<float> out, std::int64_t first_sample, float sigma);
  /// out[k] += sigma * (N(0,1) + j N(0,1)) for complex samples (draws 2n and 2n+1).
  /// Use one IndexedNoise for either real or complex samples, not both.
  void add_complex(std::span<std::complex<float>> out, std::int64_t first_sample, float sigma_per_component);
  /// The draw this generator produces next without reseeding or skipping.
  std::int64_t next_draw() const { return position_; }

 private:
  template <bool kAdd>
  void draws(float* out, std::int64_t count, std::int64_t first_draw, float sigma);
  void seek(std::int64_t draw);

  std::uint64_t seed_;
  GaussianNoise stream_;
  std::int64_t position_ = 0;  ///< index of the draw stream_ produces next
};

}  // namespace deepnav
