#include "receiver/file_sample_source.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <sys/types.h>

namespace deepnav {
namespace {

// Samples per fread: bounds the memory of the source whatever the caller asks for.
constexpr std::size_t kChunkSamples = 1 << 16;
// gr_complex values are scaled so that the RMS of the first chunk lands here:
// 2048 leaves 24 dB of headroom below int16 full scale (no clipping of Gaussian
// noise or moderate interference) while the quantisation step stays ~66 dB
// below the RMS, far below any loss the receiver would notice.
constexpr double kTargetRms = 2048.0;

std::int16_t saturate_int16(float value) {
  const float rounded = std::nearbyint(value);
  return static_cast<std::int16_t>(std::clamp(rounded, -32768.0f, 32767.0f));
}

}  // namespace

FileSampleSource::FileSampleSource(FileSampleSourceOptions options) : options_(std::move(options)) {
  const std::string name = options_.path.string();
  if (!(options_.sample_rate_hz > 0.0) || !std::isfinite(options_.sample_rate_hz))
    throw std::invalid_argument(
        fmt::format("sample file '{}': sample rate must be a positive number of Hz, got {}", name,
                    options_.sample_rate_hz));
  if (!(options_.skip_s >= 0.0) || !std::isfinite(options_.skip_s))
    throw std::invalid_argument(
        fmt::format("sample file '{}': skip must be zero or a positive number of seconds, got {}", name,
                    options_.skip_s));

  file_ = std::fopen(name.c_str(), "rb");
  if (file_ == nullptr)
    throw std::runtime_error(fmt::format("cannot open sample file '{}': {}", name, std::strerror(errno)));
  std::error_code ec;
  const auto size_bytes = std::filesystem::file_size(options_.path, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot read the size of sample file '{}': {}", name, ec.message()));
  const std::size_t bps = bytes_per_sample(options_.format);
  if (size_bytes == 0) throw std::runtime_error(fmt::format("sample file '{}' is empty", name));
  total_samples_ = static_cast<std::int64_t>(size_bytes / bps);
  if (const auto trailing = size_bytes % bps; trailing != 0)
    warnings_.push_back(fmt::format(
        "sample file '{}': its last {} byte(s) are ignored (a partial sample: the size {} is not a multiple of "
        "the {} bytes of one {} sample)",
        name, trailing, size_bytes, bps, to_string(options_.format)));
  if (total_samples_ == 0)
    throw std::runtime_error(
        fmt::format("sample file '{}' holds no whole {} sample ({} bytes)", name, to_string(options_.format),
                    size_bytes));

  const auto skip_samples = static_cast<std::int64_t>(std::llround(options_.skip_s * options_.sample_rate_hz));
  if (skip_samples >= total_samples_)
    throw std::runtime_error(fmt::format("sample file '{}': skip of {} s ({} samples) is past its end ({} samples)",
                                         name, options_.skip_s, skip_samples, total_samples_));
  next_index_ = skip_samples;
  if (::fseeko(file_, static_cast<off_t>(skip_samples) * static_cast<off_t>(bps), SEEK_SET) != 0)
    throw std::runtime_error(fmt::format("cannot seek in sample file '{}': {}", name, std::strerror(errno)));
  if (options_.format == SampleFormat::gr_complex) choose_float_scale();
}

FileSampleSource::~FileSampleSource() {
  if (file_ != nullptr) std::fclose(file_);
}

void FileSampleSource::choose_float_scale() {
  const off_t start = ::ftello(file_);
  const std::size_t count = read_raw(kChunkSamples);
  double power = 0.0;
  for (std::size_t i = 0; i < 2 * count; ++i) {
    float v;
    std::memcpy(&v, raw_.data() + 4 * i, sizeof v);
    if (std::isfinite(v)) power += static_cast<double>(v) * v;
  }
  const double rms = count > 0 ? std::sqrt(power / static_cast<double>(count)) : 0.0;
  // An all-zero start gives no level to go by; unit scale at least keeps zeros zero.
  float_scale_ = rms > 0.0 ? static_cast<float>(kTargetRms / rms) : 1.0f;
  if (::fseeko(file_, start, SEEK_SET) != 0)
    throw std::runtime_error(
        fmt::format("cannot seek in sample file '{}': {}", options_.path.string(), std::strerror(errno)));
}

std::size_t FileSampleSource::read_raw(std::size_t max_samples) {
  const std::size_t bps = bytes_per_sample(options_.format);
  const auto left = static_cast<std::size_t>(total_samples_ - next_index_);
  const std::size_t wanted = std::min({max_samples, kChunkSamples, left});
  raw_.resize(wanted * bps);
  const std::size_t got = wanted == 0 ? 0 : std::fread(raw_.data(), bps, wanted, file_);
  if (got < wanted && std::ferror(file_))
    throw std::runtime_error(
        fmt::format("error reading sample file '{}': {}", options_.path.string(), std::strerror(errno)));
  return got;
}

std::size_t FileSampleSource::read(std::span<Sample> out) {
  if (at_end_ || out.empty()) return 0;
  const std::size_t count = read_raw(out.size());
  if (count == 0) {
    at_end_ = true;
    return 0;
  }
  convert(count, out);
  next_index_ += static_cast<std::int64_t>(count);
  return count;
}

void FileSampleSource::convert(std::size_t count, std::span<Sample> out) const {
  const std::int16_t q_sign = options_.inverted_spectrum ? -1 : 1;
  const unsigned char* raw = raw_.data();
  switch (options_.format) {
    case SampleFormat::ibyte:
      for (std::size_t i = 0; i < count; ++i)
        out[i] = Sample(static_cast<std::int8_t>(raw[2 * i]),
                        static_cast<std::int16_t>(q_sign * static_cast<std::int8_t>(raw[2 * i + 1])));
      break;
    case SampleFormat::ishort:
      for (std::size_t i = 0; i < count; ++i) {
        std::int16_t iq[2];
        std::memcpy(iq, raw + 4 * i, sizeof iq);
        // -(-32768) does not fit: saturate rather than wrap.
        const int q = q_sign * static_cast<int>(iq[1]);
        out[i] = Sample(iq[0], static_cast<std::int16_t>(std::min(q, 32767)));
      }
      break;
    case SampleFormat::gr_complex:
      for (std::size_t i = 0; i < count; ++i) {
        float iq[2];
        std::memcpy(iq, raw + 8 * i, sizeof iq);
        if (!std::isfinite(iq[0]) || !std::isfinite(iq[1]))
          throw std::runtime_error(fmt::format("sample file '{}': sample {} is not a finite number",
                                               options_.path.string(),
                                               next_index_ + static_cast<std::int64_t>(i)));
        out[i] = Sample(saturate_int16(iq[0] * float_scale_), saturate_int16(q_sign * iq[1] * float_scale_));
      }
      break;
    case SampleFormat::byte:
      for (std::size_t i = 0; i < count; ++i) out[i] = Sample(static_cast<std::int8_t>(raw[i]), 0);
      break;
  }
}

}  // namespace deepnav
