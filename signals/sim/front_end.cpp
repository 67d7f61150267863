#include "signals/sim/front_end.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "signals/sample_packing.hpp"
#include "signals/sim/floor_div.hpp"
#include "signals/sim/gaussian_noise.hpp"
#include "signals/sim/parallel_ranges.hpp"

namespace deepnav {
namespace {

const FrontEndConfig& validated(const FrontEndConfig& c) {
  if (!std::isfinite(c.sample_rate_hz) || c.sample_rate_hz <= 0.0)
    throw std::invalid_argument("front end sample_rate_hz = " + std::to_string(c.sample_rate_hz) + ": expected > 0");
  if (!std::isfinite(c.cn0_ref_dbhz))
    throw std::invalid_argument("front end cn0_ref_dbhz is not finite: expected a C/N0 in dB-Hz");
  validate_adc(c.adc, c.format);
  for (std::size_t j = 0; j < c.jammers.size(); ++j) {
    try {
      validate_jammer(c.jammers[j], c.sample_rate_hz, c.if_hz);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("jammers[" + std::to_string(j) + "]: " + e.what());
    }
  }
  return c;
}

/// For each worker (wanting draws from first_draws[w] on) a generator of its own: first
/// those that left off exactly there, then any left.
std::vector<std::size_t> pick_generators(const std::vector<IndexedNoise>& generators,
                                         const std::vector<std::int64_t>& first_draws) {
  const std::size_t none = generators.size();
  std::vector<std::size_t> pick(first_draws.size(), none);
  std::vector<bool> taken(generators.size(), false);
  const auto take = [&](std::size_t w, auto&& suits) {
    for (std::size_t g = 0; pick[w] == none && g < generators.size(); ++g)
      if (!taken[g] && suits(g)) {
        pick[w] = g;
        taken[g] = true;
      }
  };
  for (std::size_t w = 0; w < first_draws.size(); ++w)
    take(w, [&](std::size_t g) { return generators[g].next_draw() == first_draws[w]; });
  for (std::size_t w = 0; w < first_draws.size(); ++w) take(w, [](std::size_t) { return true; });
  return pick;
}

double sum_squares(const float* x, std::size_t n) {
  // Eight independent partial sums break the add dependency chain (and vectorise) without
  // relying on -ffast-math; one AGC window is short, so float sums are exact enough.
  float part[8] = {};
  std::size_t k = 0;
  for (; k + 8 <= n; k += 8)
    for (int l = 0; l < 8; ++l) part[l] += x[k + l] * x[k + l];
  double s = 0.0;
  for (; k < n; ++k) s += static_cast<double>(x[k]) * x[k];
  for (float p : part) s += p;
  return s;
}

}  // namespace

FrontEnd::FrontEnd(FrontEndConfig config, std::uint64_t seed, unsigned threads)
    : config_(validated(config)),
      noise_sigma_(static_cast<float>(thermal_noise_sigma(config_.sample_rate_hz))),
      threads_(std::max(1u, threads)),
      noise_(threads_, IndexedNoise(splitmix64(seed))),
      agc_(config_.adc, config_.sample_rate_hz) {
  for (std::size_t j = 0; j < config_.jammers.size(); ++j)
    jammers_.emplace_back(config_.jammers[j], config_.sample_rate_hz, config_.if_hz, config_.cn0_ref_dbhz,
                          splitmix64(seed ^ (0xA5A5A5A5ULL + j)));
}

void FrontEnd::process(std::span<std::complex<float>> block, std::int64_t first_sample,
                       std::vector<std::byte>& out_bytes) {
  const std::size_t spw = samples_per_word(config_.format);
  if (block.size() % spw != 0)
    throw std::logic_error("FrontEnd::process: " + to_string(config_.format) + " needs blocks of whole words of " +
                           std::to_string(spw) + " samples");
  out_bytes.resize(block.size() / spw * bytes_per_word(config_.format));
  for (Jammer& jammer : jammers_) jammer.add_to(block, first_sample);
  if (!is_complex(config_.format)) real_.resize(block.size());
  add_thermal_noise(block, first_sample);
  if (is_complex(config_.format))
    digitize(reinterpret_cast<const float*>(block.data()), block.size(), 2, first_sample, out_bytes.data());
  else digitize(real_.data(), block.size(), 1, first_sample, out_bytes.data());
}

void FrontEnd::add_thermal_noise(std::span<std::complex<float>> block, std::int64_t first_sample) {
  const bool complex = is_complex(config_.format);
  // Samples per noise chunk: complex samples take two draws each.
  const std::int64_t piece = complex ? IndexedNoise::kChunkDraws / 2 : IndexedNoise::kChunkDraws;
  const auto size = static_cast<std::int64_t>(block.size());
  if (size == 0) return;
  const std::int64_t first_piece = floor_div(first_sample, piece);
  const std::int64_t pieces = floor_div(first_sample + size - 1, piece) - first_piece + 1;
  const float root2 = std::sqrt(2.0f);
  // The ranges run_in_ranges gives the workers, and for each the generator to use.
  const int workers = range_workers(threads_, static_cast<int>(pieces));
  const auto range_start = [&](int w) {
    return std::max(first_sample, (first_piece + range_begin(static_cast<int>(pieces), workers, w)) * piece);
  };
  const std::int64_t draws_per_sample = complex ? 2 : 1;
  std::vector<std::int64_t> first_draws;
  for (int w = 0; w < workers; ++w) first_draws.push_back(range_start(w) * draws_per_sample);
  const std::vector<std::size_t> generator = pick_generators(noise_, first_draws);
  run_in_ranges(threads_, static_cast<int>(pieces), [&](int worker, int a, int b) {
    const std::int64_t s0 = std::max(first_sample, (first_piece + a) * piece);
    const std::int64_t s1 = std::min(first_sample + size, (first_piece + b) * piece);
    const auto offset = static_cast<std::size_t>(s0 - first_sample), count = static_cast<std::size_t>(s1 - s0);
    IndexedNoise& noise = noise_[generator[static_cast<std::size_t>(worker)]];
    if (complex) {
      if (config_.thermal_noise) noise.add_complex(block.subspan(offset, count), s0, noise_sigma_);
      return;
    }
    for (std::size_t k = offset; k < offset + count; ++k) real_[k] = root2 * block[k].real();
    if (config_.thermal_noise) noise.add_real(std::span<float>(real_.data() + offset, count), s0, noise_sigma_);
  });
}

// Segments end at AGC window boundaries (absolute multiples of Agc::kWindow samples) so
// the gain sequence does not depend on how the run is cut into blocks.
void FrontEnd::digitize(const float* x, std::size_t n_samples, int values_per_sample, std::int64_t first_sample,
                        std::byte* out) {
  const auto vps = static_cast<std::size_t>(values_per_sample);
  const bool packed = is_packed(config_.format);
  // Packed formats: the levels of the whole block first, then whole words of them.
  if (packed) levels_.resize(n_samples * vps);
  const std::size_t bytes_per_value = packed ? 0 : bytes_per_sample(config_.format) / vps;
  for (std::size_t k = 0; k < n_samples;) {
    const std::int64_t sample = first_sample + static_cast<std::int64_t>(k);
    const std::int64_t in_window = ((sample % Agc::kWindow) + Agc::kWindow) % Agc::kWindow;
    const std::size_t len = std::min<std::size_t>(static_cast<std::size_t>(Agc::kWindow - in_window), n_samples - k);
    const float* seg = x + k * vps;
    const double energy = sum_squares(seg, len * vps);
    if (!agc_.initialized()) agc_.initialize(energy / static_cast<double>(len * vps));
    if (packed) {
      quantize_levels(seg, len * vps, agc_.gain(), config_.adc.bits, levels_.data() + k * vps);
    } else {
      quantize_pack(seg, len * vps, agc_.gain(), config_.adc.bits, config_.format, out + k * vps * bytes_per_value);
    }
    agc_.accumulate(energy, len * vps, in_window + static_cast<std::int64_t>(len) == Agc::kWindow);
    k += len;
  }
  if (packed && config_.format.packed.q_first)  // the layout stores Q before I
    for (std::size_t k = 0; k + 1 < levels_.size(); k += 2) std::swap(levels_[k], levels_[k + 1]);
  if (packed)
    pack_levels(
        levels_, config_.format.packed,
        std::span<std::byte>(out, n_samples / samples_per_word(config_.format) * bytes_per_word(config_.format)));
}

}  // namespace deepnav
