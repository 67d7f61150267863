#pragma once
// LNAV word parity: the (32,26) Hamming code of IS-GPS-200 20.3.5 / Table 20-XIV.
//
// A word is held in the low 30 bits of a uint32: bit 29 is word bit 1 (sent first), bit 0 is
// word bit 30 (D30). Source data d1..d24 are held in the low 24 bits of a uint32 with d1 at bit 23.
// Each word depends on D29*, D30*, the last two transmitted bits of the previous word.
#include <cstdint>
#include <optional>

namespace deepnav::lnav {

inline constexpr std::uint32_t kDataMask = 0xFFFFFFu;
inline constexpr std::uint32_t kWordMask = 0x3FFFFFFFu;

/// The six parity bits D25..D30 (D25 in bit 5) of source data d1..d24.
std::uint32_t parity_bits(std::uint32_t data24, bool prev_d29, bool prev_d30);

/// The 30 transmitted bits: d1..d24, complemented when D30* = 1, followed by the parity.
std::uint32_t encode_word(std::uint32_t data24, bool prev_d29, bool prev_d30);

/// Checks a received word against D29*, D30* and returns d1..d24 with the polarity restored
/// (un-complemented when D30* = 1); nullopt when the parity fails.
std::optional<std::uint32_t> check_word(std::uint32_t word30, bool prev_d29, bool prev_d30);

/// Sets the non-information bits d23, d24 (IS-GPS-200 20.3.5.2; words 2 and 10) so that the
/// encoded word ends in D29 = D30 = 0, which makes the next word start uncomplemented.
std::uint32_t with_noninformation_bits(std::uint32_t data24, bool prev_d29, bool prev_d30);

/// D29 and D30 of a transmitted 30-bit word: the D29*, D30* of the word that follows it.
inline bool word_d29(std::uint32_t word30) { return (word30 >> 1) & 1u; }
inline bool word_d30(std::uint32_t word30) { return word30 & 1u; }

}  // namespace deepnav::lnav
