#include "receiver/file_sample_source.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepnav {
namespace {

// Samples per read: bounds the memory of the source whatever the caller asks for.
constexpr std::size_t kChunkSamples = 1 << 16;

FileSampleSourceOptions checked(FileSampleSourceOptions o) {
  if (!(o.sample_rate_hz > 0.0) || !std::isfinite(o.sample_rate_hz))
    throw std::invalid_argument(fmt::format("sample file '{}': sample rate must be a positive number of Hz, got {}",
                                            o.path.string(), o.sample_rate_hz));
  if (!(o.skip_s >= 0.0) || !std::isfinite(o.skip_s))
    throw std::invalid_argument(fmt::format(
        "sample file '{}': skip must be zero or a positive number of seconds, got {}", o.path.string(), o.skip_s));
  return o;
}

}  // namespace

FileSampleSource::FileSampleSource(FileSampleSourceOptions options)
    : options_(checked(std::move(options))),
      file_(IfFileStreamOptions{options_.path, options_.format, options_.sample_rate_hz,
                                options_.intermediate_frequency_hz, std::nullopt}),
      converter_(options_.format, options_.inverted_spectrum) {
  const auto skip_samples = static_cast<std::int64_t>(std::llround(options_.skip_s * options_.sample_rate_hz));
  if (skip_samples >= total_samples())
    throw std::runtime_error(fmt::format("sample file '{}': skip of {} s ({} samples) is past its end ({} samples)",
                                         options_.path.string(), options_.skip_s, skip_samples, total_samples()));
  file_.seek(skip_samples);
  if (options_.format == SampleFormat::gr_complex) choose_float_scale();
}

void FileSampleSource::choose_float_scale() {
  file_.peek(raw_, SampleConverter::kCalibrationSamples);
  converter_.calibrate(std::span<const std::byte>(raw_));
}

std::size_t FileSampleSource::read(std::span<Sample> out) {
  if (at_end_ || out.empty()) return 0;
  const std::int64_t first = file_.next_sample_index();
  const std::size_t count = file_.read(raw_, std::min(out.size(), kChunkSamples));
  if (count == 0) {
    at_end_ = true;
    return 0;
  }
  convert(out, first);
  return count;
}

void FileSampleSource::convert(std::span<Sample> out, std::int64_t first_index) const {
  try {
    converter_.convert(std::span<const std::byte>(raw_), out, first_index);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("sample file '{}': {}", options_.path.string(), e.what()));
  }
}

}  // namespace deepnav
