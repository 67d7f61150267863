// Raw IF bytes -> samples (receiver/sources/sample_converter.hpp) in every sample format: the
// input's first three bytes choose the format (a packed one's whole layout) and the
// spectrum inversion, the rest are the samples. Packed and cu8 samples must come out as
// the odd quantizer levels their bits allow.
#include <array>
#include <cstdlib>
#include <vector>

#include "receiver/sources/sample_converter.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using deepnav::PackedLayout;
using deepnav::SampleFormat;
using deepnav::SampleKind;

PackedLayout layout_from(std::uint8_t a, std::uint8_t b) {
  PackedLayout l;
  l.bits = std::array{1, 2, 4}[a % 3];
  l.complex = (a >> 2) & 1;
  l.q_first = l.complex && ((a >> 3) & 1);
  l.encoding = static_cast<deepnav::PackedEncoding>((a >> 4) % 3);
  l.order = static_cast<deepnav::PackedOrder>(b % 3);
  l.word_bytes = std::array{1, 2, 4}[(b >> 2) % 3];
  l.big_endian = l.word_bytes > 1 && ((b >> 4) & 1);
  return l;
}

SampleFormat format_from(std::uint8_t kind, std::uint8_t a, std::uint8_t b) {
  switch (kind % 6) {
    case 0:
      return SampleFormat::ibyte;
    case 1:
      return SampleFormat::ishort;
    case 2:
      return SampleFormat::gr_complex;
    case 3:
      return SampleFormat::byte;
    case 4:
      return SampleFormat::cu8;
    default:
      return SampleFormat::packed_format(layout_from(a, b));
  }
}

/// The largest level a component can take, for the formats whose levels are odd.
int odd_level_limit(const SampleFormat& f) {
  if (f.kind == SampleKind::cu8) return 255;
  if (f.kind == SampleKind::packed) return (1 << f.packed.bits) - 1;
  return 0;
}

void check_levels(const SampleFormat& f, std::span<const deepnav::Sample> samples) {
  const int limit = odd_level_limit(f);
  if (limit == 0) return;
  const bool complex = deepnav::is_complex(f);
  for (const deepnav::Sample& s : samples) {
    for (int v : {int{s.real()}, complex ? int{s.imag()} : 1}) {
      if (std::abs(v) > limit || v % 2 == 0)
        deepnav::fuzz::broken_promise("level " + std::to_string(v) + " is not an odd level within +-" +
                                      std::to_string(limit) + " of " + deepnav::to_string(f));
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  const SampleFormat format = format_from(data[0], data[1], data[2]);
  const bool inverted = (data[2] >> 7) & 1;
  const std::span<const std::byte> raw(reinterpret_cast<const std::byte*>(data + 3), size - 3);
  deepnav::SampleConverter converter(format, inverted);
  if (converter.needs_calibration()) converter.calibrate(raw);
  const std::size_t words = raw.size() / deepnav::bytes_per_word(format);
  std::vector<deepnav::Sample> out(words * deepnav::samples_per_word(format));
  // A non-finite gr_complex value is the one documented error.
  if (deepnav::fuzz::guarded([&] { converter.convert(raw, out, 0); }, deepnav::fuzz::is_a<std::runtime_error>))
    check_levels(format, out);
  return 0;
}
