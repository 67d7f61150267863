#include "signals/galileo/inav_fec.hpp"

// fec.h declares C functions without extern "C" of its own.
extern "C" {
#include <fec.h>
}

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace deepnav::galileo::inav {
namespace {

constexpr int kConstraintLength = 7;
constexpr int kPagePartBits = kPagePartDataBits + kTailBits;

/// Whether a generator taps delay `delay` (0: the current input): its binary digits from the
/// most significant one are the taps from the input on (ICD Figure 13).
bool taps(int generator, int delay) { return (generator >> (kConstraintLength - 1 - delay)) & 1; }

struct ViterbiDeleter {
  void operator()(void* decoder) const { delete_viterbi27(decoder); }
};
using ViterbiDecoder = std::unique_ptr<void, ViterbiDeleter>;

/// A libfec rate-1/2 K=7 decoder for the I/NAV code. libfec keeps the code's polynomials in
/// process-wide tables of the instruction set it picks when its first decoder is made, and
/// fills them with its defaults then: the first decoder is made, and the polynomials set, once
/// and alone, so that no later one races with it. Its registers hold the newest bit lowest:
/// the generators bit-reversed (171 -> 0x4f, 133 -> 0x6d); a negative one marks an inverted
/// symbol. This is the CCSDS convention, which Galileo follows.
ViterbiDecoder make_decoder() {
  static std::once_flag tables_ready;
  std::call_once(tables_ready, [] {
    const ViterbiDecoder first(create_viterbi27(kPagePartDataBits));
    if (!first) throw std::runtime_error("I/NAV Viterbi decoder: libfec could not allocate a decoder");
    int polynomials[2] = {0x4f, -0x6d};
    set_viterbi27_polynomial(polynomials);
  });
  ViterbiDecoder decoder(create_viterbi27(kPagePartDataBits));
  if (!decoder) throw std::runtime_error("I/NAV Viterbi decoder: libfec could not allocate a decoder");
  return decoder;
}

/// libfec's soft symbol: 0 a sure logic 0, 255 a sure logic 1. Levels are scaled by their mean
/// magnitude and clipped at twice it, so that a few large samples do not swamp the rest.
std::array<unsigned char, kPagePartSymbols> to_libfec_symbols(const PagePartSoftSymbols& levels) {
  double mean_magnitude = 0.0;
  for (float s : levels) mean_magnitude += std::abs(s);
  mean_magnitude /= kPagePartSymbols;
  std::array<unsigned char, kPagePartSymbols> out{};
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const double unit = mean_magnitude > 0.0 ? std::clamp(levels[i] / (2.0 * mean_magnitude), -1.0, 1.0) : 0.0;
    out[i] = static_cast<unsigned char>(std::lround(127.5 - 127.5 * unit));
  }
  return out;
}

}  // namespace

PagePartSymbols convolutional_encode(const PagePartBits& bits) {
  PagePartSymbols symbols{};
  std::array<std::uint8_t, kConstraintLength> reg{};  // reg[0]: current input, reg[k]: k bits ago
  for (int i = 0; i < kPagePartBits; ++i) {
    std::copy_backward(reg.begin(), reg.end() - 1, reg.end());
    reg[0] = i < kPagePartDataBits ? bits[static_cast<std::size_t>(i)] & 1 : 0;
    std::uint8_t g1 = 0, g2 = 0;
    for (int k = 0; k < kConstraintLength; ++k) {
      if (taps(kGeneratorG1, k)) g1 ^= reg[static_cast<std::size_t>(k)];
      if (taps(kGeneratorG2, k)) g2 ^= reg[static_cast<std::size_t>(k)];
    }
    symbols[static_cast<std::size_t>(2 * i)] = g1;
    symbols[static_cast<std::size_t>(2 * i + 1)] = g2 ^ 1;  // G2 inverted
  }
  return symbols;
}

PagePartSymbols interleave(const PagePartSymbols& coded) {
  PagePartSymbols out{};
  for (int r = 0; r < kInterleaverRows; ++r) {
    for (int c = 0; c < kInterleaverColumns; ++c) {
      out[static_cast<std::size_t>(r * kInterleaverColumns + c)] =
          coded[static_cast<std::size_t>(c * kInterleaverRows + r)];
    }
  }
  return out;
}

PagePartSoftSymbols deinterleave(const PagePartSoftSymbols& received) {
  PagePartSoftSymbols out{};
  for (int r = 0; r < kInterleaverRows; ++r) {
    for (int c = 0; c < kInterleaverColumns; ++c) {
      out[static_cast<std::size_t>(c * kInterleaverRows + r)] =
          received[static_cast<std::size_t>(r * kInterleaverColumns + c)];
    }
  }
  return out;
}

PagePartBits viterbi_decode(const PagePartSoftSymbols& deinterleaved) {
  const ViterbiDecoder decoder = make_decoder();
  std::array<unsigned char, kPagePartSymbols> symbols = to_libfec_symbols(deinterleaved);
  init_viterbi27(decoder.get(), 0);
  update_viterbi27_blk(decoder.get(), symbols.data(), kPagePartBits);
  std::array<unsigned char, (kPagePartDataBits + 7) / 8> packed{};
  chainback_viterbi27(decoder.get(), packed.data(), kPagePartDataBits, 0);
  PagePartBits bits{};
  for (std::size_t i = 0; i < bits.size(); ++i) bits[i] = (packed[i / 8] >> (7 - i % 8)) & 1;  // first bit highest
  return bits;
}

PagePartSymbols encode_page_part(const PagePartBits& bits) { return interleave(convolutional_encode(bits)); }

PagePartBits decode_page_part(const PagePartSoftSymbols& received) { return viterbi_decode(deinterleave(received)); }

}  // namespace deepnav::galileo::inav
