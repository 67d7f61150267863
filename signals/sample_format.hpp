#pragma once
// IF sample formats, named as GNSS-SDR names them, with the common aliases.
#include <cstddef>
#include <string>
#include <string_view>

namespace deepnav {

enum class SampleFormat {
  ibyte,       ///< interleaved int8 I/Q (alias cs8)
  ishort,      ///< interleaved int16 I/Q, little endian (alias cs16)
  gr_complex,  ///< complex float32 I/Q, little endian (alias cf32)
  byte,        ///< real int8 samples (alias s8)
  cu8,         ///< interleaved unsigned 8-bit I/Q, zero at 127.5 (RTL-SDR, rtl_tcp)
};

/// Accepts ibyte/cs8, ishort/cs16, gr_complex/cf32, byte/s8, cu8 (case-sensitive);
/// throws std::invalid_argument naming the valid choices otherwise.
SampleFormat parse_sample_format(std::string_view name);
std::string_view to_string(SampleFormat format);
/// Bytes of one sample (one complex I/Q pair, or one real value).
std::size_t bytes_per_sample(SampleFormat format);
bool is_complex(SampleFormat format);
/// The list of accepted names, for help texts and error messages.
std::string sample_format_choices();

}  // namespace deepnav
