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
}  // namespace

FileSampleSource::FileSampleSource(FileSampleSourceOptions options)
    : options_(std::move(options)), converter_(options_.format, options_.inverted_spectrum) {
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
  const std::size_t count = read_raw(SampleConverter::kCalibrationSamples);
  converter_.calibrate(std::as_bytes(std::span(raw_.data(), count * bytes_per_sample(options_.format))));
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
  try {
    converter_.convert(std::as_bytes(std::span(raw_.data(), count * bytes_per_sample(options_.format))), out,
                       next_index_);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("sample file '{}': {}", options_.path.string(), e.what()));
  }
}

}  // namespace deepnav
