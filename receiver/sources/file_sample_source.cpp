#include "receiver/sources/file_sample_source.hpp"

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
                                options_.intermediate_frequency_hz, std::nullopt, options_.header_bytes,
                                options_.footer_bytes, options_.length_bytes}),
      converter_(options_.format, options_.inverted_spectrum) {
  const auto skip_samples = static_cast<std::int64_t>(std::llround(options_.skip_s * options_.sample_rate_hz));
  if (skip_samples >= total_samples())
    throw std::runtime_error(fmt::format("sample file '{}': skip of {} s ({} samples) is past its end ({} samples)",
                                         options_.path.string(), options_.skip_s, skip_samples, total_samples()));
  // A packed file is read in whole words: start at the word holding the first sample wanted
  // and hold back the samples of that word before it.
  const auto spw = static_cast<std::int64_t>(samples_per_word(options_.format));
  file_.seek(skip_samples - skip_samples % spw);
  if (skip_samples % spw != 0) {
    fill_pending();
    pending_at_ = static_cast<std::size_t>(skip_samples % spw);
  }
  if (options_.format == SampleFormat::gr_complex) choose_float_scale();
}

void FileSampleSource::fill_pending() {
  const std::int64_t first = file_.next_sample_index();
  const std::size_t count = file_.read(raw_, samples_per_word(options_.format));
  pending_.resize(count);
  pending_at_ = 0;
  convert(pending_, first);
}

void FileSampleSource::choose_float_scale() {
  file_.peek(raw_, SampleConverter::kCalibrationSamples);
  converter_.calibrate(std::span<const std::byte>(raw_));
}

std::size_t FileSampleSource::read(std::span<Sample> out) {
  if (at_end_ || out.empty()) return 0;
  // Samples of a word read before (after a skip into it, or for a read shorter than a word)
  // come first; the read goes on from the file after them, so that a skip into a packed
  // word does not make the first read a few samples long.
  const std::size_t held = std::min(out.size(), pending_.size() - pending_at_);
  std::copy_n(pending_.begin() + static_cast<std::ptrdiff_t>(pending_at_), held, out.begin());
  pending_at_ += held;
  const std::size_t count = held + read_file(out.subspan(held));
  if (count == 0) at_end_ = true;
  return count;
}

std::size_t FileSampleSource::read_file(std::span<Sample> out) {
  if (out.empty()) return 0;
  if (out.size() < samples_per_word(options_.format)) {
    fill_pending();
    const std::size_t n = std::min(out.size(), pending_.size());
    std::copy_n(pending_.begin(), n, out.begin());
    pending_at_ = n;
    return n;
  }
  const std::int64_t first = file_.next_sample_index();
  const std::size_t count = file_.read(raw_, std::min(out.size(), kChunkSamples));
  if (count > 0) convert(out, first);
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
