#include "signals/sample_format.hpp"

#include <fmt/format.h>

#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

namespace deepnav {
namespace {

constexpr std::array<std::pair<std::string_view, SampleKind>, 9> kNames = {{
    {"ibyte", SampleKind::ibyte},
    {"cs8", SampleKind::ibyte},
    {"ishort", SampleKind::ishort},
    {"cs16", SampleKind::ishort},
    {"gr_complex", SampleKind::gr_complex},
    {"cf32", SampleKind::gr_complex},
    {"byte", SampleKind::byte},
    {"s8", SampleKind::byte},
    {"cu8", SampleKind::cu8},
}};

/// GNSS-SDR's names for packed layouts, as the tokens they stand for.
constexpr std::array<std::pair<std::string_view, std::string_view>, 3> kPackedAliases = {{
    {"two_bit_packed", "packed2"},
    {"two_bit_cpx", "packed2_qi_msb"},
    {"four_bit_cpx", "packed4_iq"},
}};

constexpr std::string_view kPackedGrammar =
    "packed<1|2|4>[_real|_iq|_qi][_tc|_sm|_ob][_lsb|_msb|_bytemsb][_w8|_w16le|_w16be|_w32le|_w32be]";

std::vector<std::string_view> split_tokens(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find('_', start), s.size());
    out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

/// Applies tokens (from `first` on) to a layout. `given` marks the token classes the user
/// has set (a class given twice is an error); an alias's own tokens may be overridden.
void apply_tokens(const std::vector<std::string_view>& tokens, std::size_t first, PackedLayout& l, bool user,
                  std::array<bool, 4>& given, std::string_view name) {
  auto take = [&](int cls, std::string_view token) {
    if (user && given[static_cast<std::size_t>(cls)])
      throw std::invalid_argument(
          fmt::format("sample format '{}': token '{}' repeats what an earlier token set", name, token));
    if (user) given[static_cast<std::size_t>(cls)] = true;
  };
  for (std::size_t i = first; i < tokens.size(); ++i) {
    const std::string_view t = tokens[i];
    if (t == "real" || t == "iq" || t == "qi") {
      take(0, t);
      l.complex = t != "real";
      l.q_first = t == "qi";
    } else if (t == "tc" || t == "sm" || t == "ob") {
      take(1, t);
      l.encoding = t == "tc"   ? PackedEncoding::twos_complement
                   : t == "sm" ? PackedEncoding::sign_magnitude
                               : PackedEncoding::offset_binary;
    } else if (t == "lsb" || t == "msb" || t == "bytemsb") {
      take(2, t);
      l.order = t == "lsb" ? PackedOrder::lsb : t == "msb" ? PackedOrder::msb : PackedOrder::byte_msb;
    } else if (t == "w8" || t == "w16le" || t == "w16be" || t == "w32le" || t == "w32be") {
      take(3, t);
      l.word_bytes = t == "w8" ? 1 : t.substr(0, 3) == "w16" ? 2 : 4;
      l.big_endian = t.ends_with("be");
    } else {
      throw std::invalid_argument(fmt::format("sample format '{}': unknown token '{}' (expected {})", name,
                                              t.empty() ? std::string_view("(empty)") : t, kPackedGrammar));
    }
  }
}

SampleFormat parse_packed(std::string_view name) {
  std::vector<std::string_view> base, user;
  for (const auto& [alias, tokens] : kPackedAliases) {
    if (name == alias || (name.starts_with(alias) && name.size() > alias.size() && name[alias.size()] == '_')) {
      base = split_tokens(tokens);
      if (name.size() > alias.size()) user = split_tokens(name.substr(alias.size() + 1));
      break;
    }
  }
  if (base.empty()) {
    base = split_tokens(name);
    user.assign(base.begin() + 1, base.end());
    base.resize(1);
  }
  PackedLayout l;
  if (base.front() == "packed1") {
    l.bits = 1;
  } else if (base.front() == "packed2") {
    l.bits = 2;
  } else if (base.front() == "packed4") {
    l.bits = 4;
  } else {
    throw std::invalid_argument(
        fmt::format("sample format '{}': packed formats have 1, 2 or 4 bits a value ({})", name, kPackedGrammar));
  }
  std::array<bool, 4> given{};
  apply_tokens(base, 1, l, false, given, name);
  apply_tokens(user, 0, l, true, given, name);
  if (l.word_bytes == 1 && l.order == PackedOrder::byte_msb) l.order = PackedOrder::msb;  // the same thing
  return SampleFormat::packed_format(l);
}

}  // namespace

SampleFormat parse_sample_format(std::string_view name) {
  for (const auto& [text, kind] : kNames)
    if (text == name) return SampleFormat{kind, {}};
  if (name.starts_with("packed")) return parse_packed(name);
  for (const auto& [alias, tokens] : kPackedAliases)
    if (name.starts_with(alias)) return parse_packed(name);
  throw std::invalid_argument("unknown sample format '" + std::string(name) + "' (expected one of " +
                              sample_format_choices() + ")");
}

std::string to_string(const SampleFormat& format) {
  switch (format.kind) {
    case SampleKind::ibyte:
      return "ibyte";
    case SampleKind::ishort:
      return "ishort";
    case SampleKind::gr_complex:
      return "gr_complex";
    case SampleKind::byte:
      return "byte";
    case SampleKind::cu8:
      return "cu8";
    case SampleKind::packed:
      break;
  }
  const PackedLayout& l = format.packed;
  std::string s = fmt::format("packed{}", l.bits);
  if (l.complex) s += l.q_first ? "_qi" : "_iq";
  if (l.encoding == PackedEncoding::sign_magnitude) s += "_sm";
  if (l.encoding == PackedEncoding::offset_binary) s += "_ob";
  if (l.order == PackedOrder::msb) s += "_msb";
  if (l.order == PackedOrder::byte_msb) s += "_bytemsb";
  if (l.word_bytes > 1) s += fmt::format("_w{}{}", 8 * l.word_bytes, l.big_endian ? "be" : "le");
  return s;
}

bool is_complex(const SampleFormat& format) {
  if (format.kind == SampleKind::packed) return format.packed.complex;
  return format.kind != SampleKind::byte;
}

bool is_packed(const SampleFormat& format) { return format.kind == SampleKind::packed; }

std::size_t bytes_per_word(const SampleFormat& format) {
  if (format.kind == SampleKind::packed) return static_cast<std::size_t>(format.packed.word_bytes);
  return bytes_per_sample(format);
}

std::size_t samples_per_word(const SampleFormat& format) {
  if (format.kind != SampleKind::packed) return 1;
  const PackedLayout& l = format.packed;
  return static_cast<std::size_t>(8 * l.word_bytes / l.bits / (l.complex ? 2 : 1));
}

std::size_t bytes_per_sample(const SampleFormat& format) {
  switch (format.kind) {
    case SampleKind::ibyte:
      return 2;
    case SampleKind::ishort:
      return 4;
    case SampleKind::gr_complex:
      return 8;
    case SampleKind::byte:
      return 1;
    case SampleKind::cu8:
      return 2;
    case SampleKind::packed:
      break;
  }
  throw std::logic_error("bytes_per_sample: packed format " + to_string(format) +
                         " holds several samples a byte (use bytes_per_word)");
}

int value_bits(const SampleFormat& format) {
  switch (format.kind) {
    case SampleKind::ibyte:
    case SampleKind::byte:
    case SampleKind::cu8:
      return 8;
    case SampleKind::ishort:
    case SampleKind::gr_complex:
      return 16;
    case SampleKind::packed:
      return format.packed.bits;
  }
  return 8;
}

std::string sample_format_choices() {
  return "ibyte|cs8, ishort|cs16, gr_complex|cf32, byte|s8, cu8, or packed: " + std::string(kPackedGrammar) +
         " (two_bit_packed, two_bit_cpx, four_bit_cpx)";
}

}  // namespace deepnav
