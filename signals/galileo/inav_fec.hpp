#pragma once
// Forward error correction of a Galileo I/NAV page part (Galileo OS SIS ICD 4.1.4): the 114
// bits of a page part and 6 zero tail bits, convolutionally encoded at rate 1/2 with
// constraint length 7 (G1 = 171, G2 = 133 octal, the G2 symbol inverted, G1's symbol sent
// first), then block interleaved: the 240 symbols written column by column into 8 rows of 30
// columns and read row by row. Each page part is coded on its own from the zero state, to
// which its tail returns the encoder.
//
// Bits and hard symbols are logic values (0/1). Soft symbols are signal levels: logic 0 is
// positive, logic 1 negative (ICD Table 11), of any scale.
#include <array>
#include <cstdint>

namespace deepnav::galileo::inav {

inline constexpr int kPagePartDataBits = 114;  ///< even/odd, page type and the part's fields
inline constexpr int kTailBits = 6;
inline constexpr int kPagePartSymbols = 2 * (kPagePartDataBits + kTailBits);  ///< 240
inline constexpr int kInterleaverRows = 8;
inline constexpr int kInterleaverColumns = 30;
inline constexpr int kGeneratorG1 = 0171;
inline constexpr int kGeneratorG2 = 0133;

using PagePartBits = std::array<std::uint8_t, kPagePartDataBits>;
using PagePartSymbols = std::array<std::uint8_t, kPagePartSymbols>;
using PagePartSoftSymbols = std::array<float, kPagePartSymbols>;

/// The 240 code symbols of the bits followed by the tail, in coding order (not interleaved).
PagePartSymbols convolutional_encode(const PagePartBits& bits);

/// Interleaving as transmitted: output symbol r * 30 + c is coded symbol c * 8 + r.
PagePartSymbols interleave(const PagePartSymbols& coded);
/// The inverse of interleave, on soft symbols.
PagePartSoftSymbols deinterleave(const PagePartSoftSymbols& received);

/// Maximum-likelihood (Viterbi, soft decision) decoding of the 240 deinterleaved symbols of a
/// page part, tail included, back to its 114 bits.
PagePartBits viterbi_decode(const PagePartSoftSymbols& deinterleaved);

/// The 240 transmitted symbols of a page part: encoded, then interleaved.
PagePartSymbols encode_page_part(const PagePartBits& bits);
/// The bits of a page part from its 240 received soft symbols: deinterleaved, then decoded.
PagePartBits decode_page_part(const PagePartSoftSymbols& received);

}  // namespace deepnav::galileo::inav
