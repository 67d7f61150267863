#pragma once
// IF sample formats. The whole-byte formats carry GNSS-SDR's names (ibyte, ishort,
// gr_complex, byte) and the common aliases, plus cu8, the unsigned 8-bit I/Q of RTL-SDR
// dongles. Packed formats hold 1, 2 or 4 bits a value, several values to a byte, as GNSS
// front ends (MAX2769, NT1065, SiGe) write them; their layout is spelt in the name:
//
//   packed<B>[_real|_iq|_qi][_tc|_sm|_ob][_lsb|_msb|_bytemsb][_w8|_w16le|_w16be|_w32le|_w32be]
//
// B bits a value; real samples or values alternating I, Q (iq) or Q, I (qi); the code of a
// value in two's complement, sign/magnitude or offset binary (see PackedEncoding); where
// the first value of a word sits (see PackedOrder); the word the values are packed in and
// its byte order in the file. The defaults (real, tc, lsb, w8) are GNSS-SDR's
// `two_bit_packed` layout for B = 2, and these GNSS-SDR names are accepted as aliases:
// two_bit_packed = packed2 (optionally followed by more tokens, e.g. two_bit_packed_iq),
// two_bit_cpx = packed2_qi_msb, four_bit_cpx = packed4_iq.
#include <cstddef>
#include <string>
#include <string_view>

namespace deepnav {

enum class SampleKind { ibyte, ishort, gr_complex, byte, cu8, packed };

/// How a packed B-bit code stands for a quantizer level. Every encoding maps onto the odd
/// levels +-1, +-3, ..., +-(2^B - 1) of a mid-rise quantizer (the receiver's view of a
/// B-bit ADC; see signals/sim/adc.hpp).
enum class PackedEncoding {
  /// Two's complement code x is the level 2x + 1; 2 bits: 00 +1, 01 +3, 10 -3, 11 -1
  /// (GNSS-SDR's unpackers; the ION metadata standard's TC).
  twos_complement,
  /// The top bit is the sign (1: negative), the others a magnitude m: the level is
  /// +-(2m + 1); 2 bits: 00 +1, 01 +3, 10 -1, 11 -3 (MAX2769 sign/magnitude output; ION SM).
  sign_magnitude,
  /// Unsigned code u is the level 2u - (2^B - 1); 2 bits: 00 -3, 01 -1, 10 +1, 11 +3 (ION OB).
  offset_binary,
};

/// Where the values of a word are, first to last.
enum class PackedOrder {
  /// From the word's least significant bits upwards (GNSS-SDR's default,
  /// big_endian_bytes=false: the first 2-bit value of a byte in bits 1..0).
  lsb,
  /// From the word's most significant bits downwards (GNSS-SDR big_endian_bytes=true for
  /// byte items; the ION standard's left shift).
  msb,
  /// The word's bytes from the least significant one, each from its most significant bits
  /// down (GNSS-SDR short items with big_endian_bytes=true). The same as msb for 8-bit words.
  byte_msb,
};

struct PackedLayout {
  int bits = 2;          ///< bits a value: 1, 2 or 4
  bool complex = false;  ///< values alternate I and Q
  bool q_first = false;  ///< complex only: Q comes before I
  PackedEncoding encoding = PackedEncoding::twos_complement;
  PackedOrder order = PackedOrder::lsb;
  int word_bytes = 1;       ///< 1, 2 or 4
  bool big_endian = false;  ///< byte order of a multi-byte word in the file
  friend bool operator==(const PackedLayout&, const PackedLayout&) = default;
};

struct SampleFormat {
  SampleKind kind = SampleKind::ibyte;
  PackedLayout packed;  ///< used when kind == SampleKind::packed

  static const SampleFormat ibyte;       ///< interleaved int8 I/Q (alias cs8)
  static const SampleFormat ishort;      ///< interleaved int16 I/Q, little endian (alias cs16)
  static const SampleFormat gr_complex;  ///< complex float32 I/Q, little endian (alias cf32)
  static const SampleFormat byte;        ///< real int8 samples (alias s8)
  static const SampleFormat cu8;         ///< interleaved unsigned 8-bit I/Q, zero at 127.5 (RTL-SDR, rtl_tcp)
  static SampleFormat packed_format(const PackedLayout& layout) { return {SampleKind::packed, layout}; }

  friend bool operator==(const SampleFormat& a, const SampleFormat& b) {
    return a.kind == b.kind && (a.kind != SampleKind::packed || a.packed == b.packed);
  }
};

inline const SampleFormat SampleFormat::ibyte{SampleKind::ibyte, {}};
inline const SampleFormat SampleFormat::ishort{SampleKind::ishort, {}};
inline const SampleFormat SampleFormat::gr_complex{SampleKind::gr_complex, {}};
inline const SampleFormat SampleFormat::byte{SampleKind::byte, {}};
inline const SampleFormat SampleFormat::cu8{SampleKind::cu8, {}};

/// Accepts the names above (case-sensitive); throws std::invalid_argument naming the
/// valid choices, or the token of a packed name that is wrong, otherwise.
SampleFormat parse_sample_format(std::string_view name);
/// The canonical name (packed: only the tokens that differ from the defaults).
std::string to_string(const SampleFormat& format);
bool is_complex(const SampleFormat& format);
bool is_packed(const SampleFormat& format);
/// The unit a file holds whole: one sample of a whole-byte format, one word of a packed one.
std::size_t bytes_per_word(const SampleFormat& format);
/// Samples in one such unit (1 for the whole-byte formats).
std::size_t samples_per_word(const SampleFormat& format);
/// Bytes of one sample of a whole-byte format; throws std::logic_error for a packed format
/// (several samples share a byte: use bytes_per_word / samples_per_word).
std::size_t bytes_per_sample(const SampleFormat& format);
/// Bits a component value can hold: 8 (ibyte, byte, cu8), 16 (ishort; gr_complex, whose
/// floats are capped there), B (packed).
int value_bits(const SampleFormat& format);
/// The accepted names, for help texts and error messages.
std::string sample_format_choices();

}  // namespace deepnav
