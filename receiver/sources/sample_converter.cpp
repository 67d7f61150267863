#include "receiver/sources/sample_converter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "signals/sample_packing.hpp"

namespace deepnav {
namespace {

constexpr double kTargetRms = 2048.0;

std::int16_t saturate_int16(float value) {
  const float rounded = std::nearbyint(value);
  return static_cast<std::int16_t>(std::clamp(rounded, -32768.0f, 32767.0f));
}

}  // namespace

SampleValueRange converted_value_range(const SampleFormat& format) {
  switch (format.kind) {
    case SampleKind::ibyte:
    case SampleKind::byte:
      return {-128, 127};
    case SampleKind::ishort:
    case SampleKind::gr_complex:
      return {-32768, 32767};
    case SampleKind::cu8:
      return {-255, 255};
    case SampleKind::packed:
      return {-((1 << format.packed.bits) - 1), (1 << format.packed.bits) - 1};
  }
  return {-128, 127};
}

SampleConverter::SampleConverter(SampleFormat format, bool inverted_spectrum)
    : format_(format), inverted_(inverted_spectrum) {}

void SampleConverter::calibrate(std::span<const std::byte> first_samples) {
  calibrated_ = true;
  if (format_.kind != SampleKind::gr_complex) return;
  const std::size_t count = std::min(first_samples.size() / 8, kCalibrationSamples);
  double power = 0.0;
  for (std::size_t i = 0; i < 2 * count; ++i) {
    float v;
    std::memcpy(&v, first_samples.data() + 4 * i, sizeof v);
    if (std::isfinite(v)) power += static_cast<double>(v) * v;
  }
  const double rms = count > 0 ? std::sqrt(power / static_cast<double>(count)) : 0.0;
  const double scale = rms > 0.0 ? kTargetRms / rms : 0.0;
  // An all-zero start gives no level to go by, nor does one so faint (subnormal floats) that
  // its scale overflows a float: an infinite scale would turn the zeros that follow into
  // NaN (0 x inf). Unit scale at least keeps zeros zero.
  float_scale_ = scale > 0.0 && scale <= std::numeric_limits<float>::max() ? static_cast<float>(scale) : 1.0f;
}

void SampleConverter::convert(std::span<const std::byte> raw_bytes, std::span<Sample> out,
                              std::int64_t first_index) const {
  const std::size_t count = raw_bytes.size() / bytes_per_word(format_) * samples_per_word(format_);
  if (out.size() < count) throw std::logic_error("SampleConverter::convert: output too small");
  const std::int16_t q_sign = inverted_ ? -1 : 1;
  const auto* raw = reinterpret_cast<const unsigned char*>(raw_bytes.data());
  switch (format_.kind) {
    case SampleKind::ibyte:
      for (std::size_t i = 0; i < count; ++i)
        out[i] = Sample(static_cast<std::int8_t>(raw[2 * i]),
                        static_cast<std::int16_t>(q_sign * static_cast<std::int8_t>(raw[2 * i + 1])));
      break;
    case SampleKind::ishort:
      for (std::size_t i = 0; i < count; ++i) {
        std::int16_t iq[2];
        std::memcpy(iq, raw + 4 * i, sizeof iq);
        // -(-32768) does not fit: saturate rather than wrap.
        const int q = q_sign * static_cast<int>(iq[1]);
        out[i] = Sample(iq[0], static_cast<std::int16_t>(std::min(q, 32767)));
      }
      break;
    case SampleKind::gr_complex:
      for (std::size_t i = 0; i < count; ++i) {
        float iq[2];
        std::memcpy(iq, raw + 8 * i, sizeof iq);
        if (!std::isfinite(iq[0]) || !std::isfinite(iq[1]))
          throw std::runtime_error(
              fmt::format("sample {} is not a finite number", first_index + static_cast<std::int64_t>(i)));
        out[i] = Sample(saturate_int16(iq[0] * float_scale_), saturate_int16(q_sign * iq[1] * float_scale_));
      }
      break;
    case SampleKind::byte:
      for (std::size_t i = 0; i < count; ++i) out[i] = Sample(static_cast<std::int8_t>(raw[i]), 0);
      break;
    case SampleKind::cu8:
      // u - 127.5 in half units: 2u - 255, odd levels -255..255 (exact, and symmetric about zero).
      for (std::size_t i = 0; i < count; ++i)
        out[i] = Sample(static_cast<std::int16_t>(2 * raw[2 * i] - 255),
                        static_cast<std::int16_t>(q_sign * (2 * raw[2 * i + 1] - 255)));
      break;
    case SampleKind::packed: {
      const PackedLayout& l = format_.packed;
      levels_.resize(count * (l.complex ? 2 : 1));
      unpack_levels(raw_bytes.first(count / samples_per_word(format_) * bytes_per_word(format_)), l, levels_);
      if (!l.complex) {
        for (std::size_t i = 0; i < count; ++i) out[i] = Sample(levels_[i], 0);
      } else {
        const std::size_t at_i = l.q_first ? 1 : 0, at_q = 1 - at_i;
        for (std::size_t i = 0; i < count; ++i)
          out[i] = Sample(levels_[2 * i + at_i], static_cast<std::int16_t>(q_sign * levels_[2 * i + at_q]));
      }
      break;
    }
  }
}

}  // namespace deepnav
