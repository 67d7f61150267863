#pragma once
// Packed sample words <-> quantizer levels. A packed format (signals/sample_format.hpp)
// holds B-bit codes, several to a word; these functions turn whole words into the odd
// levels +-1, +-3, ..., +-(2^B - 1) they stand for, in time order (I and Q values
// alternate for complex layouts, in the layout's order), and back. The receiver reads
// files through unpack_levels, the synthesizer writes them through pack_levels, so both
// sides share one definition of every layout.
#include <cstddef>
#include <cstdint>
#include <span>

#include "signals/sample_format.hpp"

namespace deepnav {

/// Values (codes) in one word of the layout.
std::size_t values_per_word(const PackedLayout& layout);

/// Bit position (shift within the word read as an unsigned integer in the layout's byte
/// order) of the k-th value of a word, k < values_per_word.
int packed_value_shift(const PackedLayout& layout, std::size_t k);

/// levels.size() must be a whole number of words' values; out must hold those words.
/// A level outside +-(2^B - 1) or even throws std::invalid_argument (a caller's bug).
void pack_levels(std::span<const std::int16_t> levels, const PackedLayout& layout, std::span<std::byte> out);

/// Decodes in.size() / word_bytes whole words into levels (which must hold their values).
void unpack_levels(std::span<const std::byte> in, const PackedLayout& layout, std::span<std::int16_t> levels);

}  // namespace deepnav
