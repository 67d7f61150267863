#include "signals/sim/adc.hpp"

#include "signals/sample_packing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace deepnav {
namespace {

// J. Max (1960), Table II: optimum uniform step / sigma for 2^b levels, b = 1..8.
constexpr std::array<double, 8> kMaxStepOverSigma = {1.596, 0.9957, 0.5860, 0.3352, 0.1881, 0.1041, 0.0569, 0.0308};

// A float holds any level exactly; gr_complex is capped at 16 bits (value_bits).
int container_bits(const SampleFormat& format) { return value_bits(format); }

/// Odd levels fit unless the ADC fills an integer container completely (packed codes stand
/// for odd levels whatever the width).
bool stores_odd_levels(int bits, const SampleFormat& format) {
  return format == SampleFormat::gr_complex || is_packed(format) || bits < container_bits(format);
}

template <typename T>
void quantize_to(const float* x, std::size_t n, float gain, int bits, bool odd, T* out) {
  const float half_gain = 0.5f * gain;
  const float mid = std::ldexp(1.0f, bits - 1);  // 2^(b-1)
  const float max_code = 2.0f * mid - 1.0f;
  const int offset = odd ? static_cast<int>(max_code) : static_cast<int>(mid);
  const int scale = odd ? 2 : 1;
  for (std::size_t k = 0; k < n; ++k) {
    float t = x[k] * half_gain + mid;  // code units: thresholds at the integers
    t = t < 0.0f ? 0.0f : t;
    t = t > max_code ? max_code : t;
    out[k] = static_cast<T>(scale * static_cast<int>(t) - offset);
  }
}

template <typename T>
void store_little_endian(const T* values, std::size_t n, std::byte* out) {
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(out, values, n * sizeof(T));
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      std::byte b[sizeof(T)];
      std::memcpy(b, &values[k], sizeof(T));
      for (std::size_t i = 0; i < sizeof(T); ++i) out[k * sizeof(T) + i] = b[sizeof(T) - 1 - i];
    }
  }
}

template <typename T>
void load_little_endian(const std::byte* in, std::size_t n, T* values) {
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(values, in, n * sizeof(T));
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      std::byte b[sizeof(T)];
      for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = in[k * sizeof(T) + sizeof(T) - 1 - i];
      std::memcpy(&values[k], b, sizeof(T));
    }
  }
}

}  // namespace

double optimum_quantizer_rms(int bits) {
  if (bits <= 0) return 1.0;
  const double step_over_sigma =
      bits <= 8 ? kMaxStepOverSigma[static_cast<std::size_t>(bits - 1)] : 8.0 / std::ldexp(1.0, bits);
  return 2.0 / step_over_sigma;
}

void validate_adc(const AdcConfig& c, const SampleFormat& format) {
  const int max_bits = container_bits(format);
  const int min_bits = format == SampleFormat::gr_complex ? 0 : 1;
  if (c.bits < min_bits || c.bits > max_bits)
    throw std::invalid_argument(fmt::format("adc.bits = {} does not fit format {}: expected {} to {}{}", c.bits,
                                            to_string(format), min_bits, max_bits,
                                            min_bits == 0 ? " (0 = no quantization)" : ""));
  if (!std::isfinite(c.agc_target_rms) || c.agc_target_rms < 0.0)
    throw std::invalid_argument(
        fmt::format("adc.agc_target_rms = {}: expected >= 0 (0 = optimum loading)", c.agc_target_rms));
  if (c.agc_enabled && (!std::isfinite(c.agc_time_constant_s) || c.agc_time_constant_s <= 0.0))
    throw std::invalid_argument(fmt::format("adc.agc_time_constant_s = {}: expected > 0 s", c.agc_time_constant_s));
  if (!c.agc_enabled && (!std::isfinite(c.fixed_gain) || c.fixed_gain <= 0.0))
    throw std::invalid_argument(fmt::format("adc.fixed_gain = {}: expected > 0", c.fixed_gain));
}

Agc::Agc(const AdcConfig& config, double sample_rate_hz)
    : enabled_(config.agc_enabled),
      target_rms_(config.agc_target_rms > 0.0 ? config.agc_target_rms : optimum_quantizer_rms(config.bits)),
      fixed_gain_(config.fixed_gain),
      alpha_(config.agc_enabled ? -std::expm1(-kWindow / (config.agc_time_constant_s * sample_rate_hz)) : 0.0),
      gain_(static_cast<float>(config.agc_enabled ? 1.0 : config.fixed_gain)) {}

void Agc::set_gain() {
  if (!enabled_) return;
  gain_ = static_cast<float>(target_rms_ / std::sqrt(std::max(power_, 1e-30)));
}

void Agc::initialize(double power) {
  power_ = std::max(power, 0.0);
  set_gain();
}

void Agc::accumulate(double sum_squares, std::size_t values, bool window_done) {
  window_sum_ += sum_squares;
  window_values_ += values;
  if (!window_done) return;
  if (window_values_ > 0) {
    const double window_power = window_sum_ / static_cast<double>(window_values_);
    if (!initialized()) power_ = window_power;
    power_ += alpha_ * (window_power - power_);
  }
  window_sum_ = 0.0;
  window_values_ = 0;
  set_gain();
}

void quantize_levels(const float* x, std::size_t n, float gain, int bits, std::int16_t* out) {
  quantize_to(x, n, gain, bits, true, out);
}

void quantize_pack(const float* x, std::size_t n, float gain, int bits, const SampleFormat& format, std::byte* out) {
  constexpr std::size_t kChunk = 256;
  if (is_packed(format)) {
    std::vector<std::int16_t> levels(n);
    quantize_to(x, n, gain, bits, true, levels.data());
    pack_levels(levels, format.packed,
                std::span<std::byte>(out, n / values_per_word(format.packed) * bytes_per_word(format)));
    return;
  }
  if (format == SampleFormat::gr_complex) {
    float buffer[kChunk];
    for (std::size_t k0 = 0; k0 < n; k0 += kChunk) {
      const std::size_t len = std::min(kChunk, n - k0);
      if (bits == 0) {
        for (std::size_t k = 0; k < len; ++k) buffer[k] = x[k0 + k] * gain;
      } else {
        quantize_to(x + k0, len, gain, bits, true, buffer);
      }
      store_little_endian(buffer, len, out + 4 * k0);
    }
    return;
  }
  if (format == SampleFormat::cu8) {
    // The odd level L of a b-bit ADC is stored as (L + 255) / 2: an 8-bit ADC fills 0..255,
    // fewer bits sit in the middle of the range, as a dongle's ADC at low signal levels.
    std::int16_t buffer[kChunk];
    for (std::size_t k0 = 0; k0 < n; k0 += kChunk) {
      const std::size_t len = std::min(kChunk, n - k0);
      quantize_to(x + k0, len, gain, bits, true, buffer);
      for (std::size_t k = 0; k < len; ++k) out[k0 + k] = static_cast<std::byte>((buffer[k] + 255) / 2);
    }
    return;
  }
  const bool odd = stores_odd_levels(bits, format);
  if (format == SampleFormat::ishort) {
    std::int16_t buffer[kChunk];
    for (std::size_t k0 = 0; k0 < n; k0 += kChunk) {
      const std::size_t len = std::min(kChunk, n - k0);
      quantize_to(x + k0, len, gain, bits, odd, buffer);
      store_little_endian(buffer, len, out + 2 * k0);
    }
    return;
  }
  quantize_to(x, n, gain, bits, odd, reinterpret_cast<std::int8_t*>(out));
}

void unpack_levels(const std::byte* in, std::size_t n, int bits, const SampleFormat& format, float* out) {
  const bool odd = stores_odd_levels(bits, format);
  // Full-width codes c map back to the odd level 2c + 1.
  auto level = [odd](int v) { return static_cast<float>(odd ? v : 2 * v + 1); };
  switch (format.kind) {
    case SampleKind::gr_complex:
      load_little_endian(in, n, out);
      return;
    case SampleKind::ishort:
      for (std::size_t k = 0; k < n; ++k) {
        std::int16_t v;
        load_little_endian(in + 2 * k, 1, &v);
        out[k] = level(v);
      }
      return;
    case SampleKind::ibyte:
    case SampleKind::byte:
      for (std::size_t k = 0; k < n; ++k) out[k] = level(static_cast<std::int8_t>(in[k]));
      return;
    case SampleKind::cu8:
      for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<float>(2 * std::to_integer<int>(in[k]) - 255);
      return;
    case SampleKind::packed: {
      std::vector<std::int16_t> levels(n);
      unpack_levels(std::span<const std::byte>(in, n / values_per_word(format.packed) * bytes_per_word(format)),
                    format.packed, levels);
      std::copy(levels.begin(), levels.end(), out);
      return;
    }
  }
}

}  // namespace deepnav
