#include "signals/sim/indexed_noise.hpp"

#include <algorithm>
#include <vector>

#include "signals/sim/floor_div.hpp"

namespace deepnav {
namespace {

std::uint64_t chunk_seed(std::uint64_t seed, std::int64_t chunk) {
  return splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(chunk));
}

}  // namespace

IndexedNoise::IndexedNoise(std::uint64_t seed) : seed_(seed), stream_(chunk_seed(seed, 0)) {}

void IndexedNoise::seek(std::int64_t draw) {
  if (draw == position_) return;
  const std::int64_t chunk = floor_div(draw, kChunkDraws);
  std::int64_t start = chunk * kChunkDraws;
  // Continue the current stream when the target lies ahead in the same chunk.
  if (!(position_ <= draw && floor_div(position_, kChunkDraws) == chunk)) {
    stream_ = GaussianNoise(chunk_seed(seed_, chunk));
    position_ = start;
  }
  std::vector<float> skip(static_cast<std::size_t>(std::min<std::int64_t>(draw - position_, 4096)));
  while (position_ < draw) {
    const std::int64_t n = std::min<std::int64_t>(draw - position_, static_cast<std::int64_t>(skip.size()));
    stream_.fill_real(std::span<float>(skip.data(), static_cast<std::size_t>(n)), 1.0f);
    position_ += n;
  }
}

template <bool kAdd>
void IndexedNoise::draws(float* out, std::int64_t count, std::int64_t first_draw, float sigma) {
  seek(first_draw);
  while (count > 0) {
    const std::int64_t chunk_end = (floor_div(position_, kChunkDraws) + 1) * kChunkDraws;
    const std::int64_t n = std::min(count, chunk_end - position_);
    std::span<float> part(out, static_cast<std::size_t>(n));
    if constexpr (kAdd) stream_.add_real(part, sigma);
    else stream_.fill_real(part, sigma);
    out += n;
    count -= n;
    position_ += n;
    if (position_ == chunk_end) stream_ = GaussianNoise(chunk_seed(seed_, floor_div(position_, kChunkDraws)));
  }
}

void IndexedNoise::add_real(std::span<float> out, std::int64_t first_sample, float sigma) {
  draws<true>(out.data(), static_cast<std::int64_t>(out.size()), first_sample, sigma);
}

void IndexedNoise::fill_real(std::span<float> out, std::int64_t first_sample, float sigma) {
  draws<false>(out.data(), static_cast<std::int64_t>(out.size()), first_sample, sigma);
}

void IndexedNoise::add_complex(std::span<std::complex<float>> out, std::int64_t first_sample,
                               float sigma_per_component) {
  draws<true>(reinterpret_cast<float*>(out.data()), 2 * static_cast<std::int64_t>(out.size()), 2 * first_sample,
              sigma_per_component);
}

}  // namespace deepnav
