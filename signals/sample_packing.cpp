#include "signals/sample_packing.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace deepnav {
namespace {

/// The word's bytes as an unsigned integer, in the layout's byte order.
std::uint32_t load_word(const std::byte* at, const PackedLayout& l) {
  std::uint32_t w = 0;
  const auto n = static_cast<std::size_t>(l.word_bytes);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t significance = l.big_endian ? n - 1 - i : i;
    w |= std::to_integer<std::uint32_t>(at[i]) << (8 * significance);
  }
  return w;
}

void store_word(std::uint32_t w, std::byte* at, const PackedLayout& l) {
  const auto n = static_cast<std::size_t>(l.word_bytes);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t significance = l.big_endian ? n - 1 - i : i;
    at[i] = static_cast<std::byte>((w >> (8 * significance)) & 0xFFu);
  }
}

int level_of_code(unsigned code, const PackedLayout& l) {
  const int full = 1 << l.bits;
  const int half = full / 2;
  const int c = static_cast<int>(code);
  switch (l.encoding) {
    case PackedEncoding::twos_complement:
      return 2 * (c >= half ? c - full : c) + 1;
    case PackedEncoding::sign_magnitude: {
      const int m = c & (half - 1);
      return (c & half) != 0 ? -(2 * m + 1) : 2 * m + 1;
    }
    case PackedEncoding::offset_binary:
      return 2 * c - (full - 1);
  }
  return 0;
}

unsigned code_of_level(int level, const PackedLayout& l) {
  const int full = 1 << l.bits;
  if ((level & 1) == 0 || std::abs(level) > full - 1)
    throw std::invalid_argument(
        fmt::format("pack_levels: {} is not an odd level of a {}-bit quantizer", level, l.bits));
  const unsigned mask = static_cast<unsigned>(full - 1);
  switch (l.encoding) {
    case PackedEncoding::twos_complement:
      return static_cast<unsigned>((level - 1) / 2) & mask;
    case PackedEncoding::sign_magnitude:
      return (level < 0 ? static_cast<unsigned>(full / 2) : 0u) | static_cast<unsigned>((std::abs(level) - 1) / 2);
    case PackedEncoding::offset_binary:
      return static_cast<unsigned>((level + full - 1) / 2);
  }
  return 0;
}

}  // namespace

std::size_t values_per_word(const PackedLayout& l) { return static_cast<std::size_t>(8 * l.word_bytes / l.bits); }

int packed_value_shift(const PackedLayout& l, std::size_t k) {
  const int b = l.bits;
  const int word_bits = 8 * l.word_bytes;
  const int ki = static_cast<int>(k);
  switch (l.order) {
    case PackedOrder::lsb:
      return ki * b;
    case PackedOrder::msb:
      return word_bits - (ki + 1) * b;
    case PackedOrder::byte_msb: {
      const int per_byte = 8 / b;
      return 8 * (ki / per_byte) + 8 - (ki % per_byte + 1) * b;
    }
  }
  return 0;
}

void pack_levels(std::span<const std::int16_t> levels, const PackedLayout& l, std::span<std::byte> out) {
  const std::size_t vpw = values_per_word(l);
  const auto wb = static_cast<std::size_t>(l.word_bytes);
  if (levels.size() % vpw != 0 || out.size() < levels.size() / vpw * wb)
    throw std::logic_error("pack_levels: levels must fill whole words and out must hold them");
  std::vector<int> shifts(vpw);
  for (std::size_t k = 0; k < vpw; ++k) shifts[k] = packed_value_shift(l, k);
  for (std::size_t w = 0; w < levels.size() / vpw; ++w) {
    std::uint32_t word = 0;
    for (std::size_t k = 0; k < vpw; ++k) word |= code_of_level(levels[w * vpw + k], l) << shifts[k];
    store_word(word, out.data() + w * wb, l);
  }
}

void unpack_levels(std::span<const std::byte> in, const PackedLayout& l, std::span<std::int16_t> levels) {
  const std::size_t vpw = values_per_word(l);
  const auto wb = static_cast<std::size_t>(l.word_bytes);
  const std::size_t words = in.size() / wb;
  if (levels.size() < words * vpw) throw std::logic_error("unpack_levels: output too small");
  std::array<std::int16_t, 16> table{};
  for (unsigned c = 0; c < (1u << l.bits); ++c) table[c] = static_cast<std::int16_t>(level_of_code(c, l));
  std::vector<int> shifts(vpw);
  for (std::size_t k = 0; k < vpw; ++k) shifts[k] = packed_value_shift(l, k);
  const std::uint32_t mask = (1u << l.bits) - 1u;
  for (std::size_t w = 0; w < words; ++w) {
    const std::uint32_t word = load_word(in.data() + w * wb, l);
    std::int16_t* out = levels.data() + w * vpw;
    for (std::size_t k = 0; k < vpw; ++k) out[k] = table[(word >> shifts[k]) & mask];
  }
}

}  // namespace deepnav
