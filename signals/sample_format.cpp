#include "signals/sample_format.hpp"

#include <array>
#include <stdexcept>
#include <utility>

namespace deepnav {
namespace {
constexpr std::array<std::pair<std::string_view, SampleFormat>, 9> kNames = {{
    {"ibyte", SampleFormat::ibyte},
    {"cs8", SampleFormat::ibyte},
    {"ishort", SampleFormat::ishort},
    {"cs16", SampleFormat::ishort},
    {"gr_complex", SampleFormat::gr_complex},
    {"cf32", SampleFormat::gr_complex},
    {"byte", SampleFormat::byte},
    {"s8", SampleFormat::byte},
    {"cu8", SampleFormat::cu8},
}};
}  // namespace

SampleFormat parse_sample_format(std::string_view name) {
  for (const auto& [text, format] : kNames)
    if (text == name) return format;
  throw std::invalid_argument("unknown sample format '" + std::string(name) + "' (expected one of " +
                              sample_format_choices() + ")");
}

std::string_view to_string(SampleFormat format) {
  switch (format) {
    case SampleFormat::ibyte: return "ibyte";
    case SampleFormat::ishort: return "ishort";
    case SampleFormat::gr_complex: return "gr_complex";
    case SampleFormat::byte: return "byte";
    case SampleFormat::cu8: return "cu8";
  }
  return "?";
}

std::size_t bytes_per_sample(SampleFormat format) {
  switch (format) {
    case SampleFormat::ibyte: return 2;
    case SampleFormat::ishort: return 4;
    case SampleFormat::gr_complex: return 8;
    case SampleFormat::byte: return 1;
    case SampleFormat::cu8: return 2;
  }
  return 0;
}

bool is_complex(SampleFormat format) { return format != SampleFormat::byte; }

std::string sample_format_choices() { return "ibyte|cs8, ishort|cs16, gr_complex|cf32, byte|s8, cu8"; }

}  // namespace deepnav
