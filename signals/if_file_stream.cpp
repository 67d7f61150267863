#include "signals/if_file_stream.hpp"

#include <fmt/format.h>
#include <sys/types.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "ins/input_file.hpp"

namespace deepnav {

IfFileStream::IfFileStream(IfFileStreamOptions options) : options_(std::move(options)) {
  const std::string name = options_.path.string();
  if (!(options_.sample_rate_hz > 0.0) || !std::isfinite(options_.sample_rate_hz))
    throw std::invalid_argument(fmt::format("sample file '{}': sample rate must be a positive number of Hz, got {}",
                                            name, options_.sample_rate_hz));
  // A FIFO or device would block or never end; the reader needs the size and seeking.
  check_input_file(name, "sample file");
  file_ = std::fopen(name.c_str(), "rb");
  if (file_ == nullptr)
    throw std::runtime_error(fmt::format("cannot open sample file '{}': {}", name, std::strerror(errno)));
  std::error_code ec;
  const auto size_bytes = std::filesystem::file_size(options_.path, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot read the size of sample file '{}': {}", name, ec.message()));
  const std::size_t bpw = bytes_per_word(options_.format);
  if (size_bytes == 0) throw std::runtime_error(fmt::format("sample file '{}' is empty", name));
  // Compared one at a time: the sum of two sizes from a metadata file may not fit 64 bits.
  if (options_.header_bytes >= size_bytes || options_.footer_bytes >= size_bytes - options_.header_bytes)
    throw std::runtime_error(
        fmt::format("sample file '{}' ({} bytes) holds nothing beyond its {}-byte header and "
                    "{}-byte footer",
                    name, size_bytes, options_.header_bytes, options_.footer_bytes));
  std::uint64_t data_bytes = size_bytes - options_.header_bytes - options_.footer_bytes;
  if (options_.length_bytes) {
    if (*options_.length_bytes > data_bytes)
      warnings_.push_back(
          fmt::format("sample file '{}': {} bytes of samples were announced, the file holds {}: "
                      "reading those",
                      name, *options_.length_bytes, data_bytes));
    data_bytes = std::min(data_bytes, *options_.length_bytes);
  }
  total_samples_ = static_cast<std::int64_t>(data_bytes / bpw * samples_per_word(options_.format));
  if (const auto trailing = data_bytes % bpw; trailing != 0)
    warnings_.push_back(
        fmt::format("sample file '{}': its last {} byte(s) are ignored (a partial {}: the size {} is not a multiple of "
                    "the {} bytes of one {} {})",
                    name, trailing, is_packed(options_.format) ? "word" : "sample", data_bytes, bpw,
                    to_string(options_.format), is_packed(options_.format) ? "word" : "sample"));
  if (total_samples_ == 0)
    throw std::runtime_error(fmt::format("sample file '{}' holds no whole {} sample ({} bytes)", name,
                                         to_string(options_.format), data_bytes));
  if (options_.header_bytes > 0) position_at(0);
}

IfFileStream::~IfFileStream() {
  if (file_ != nullptr) std::fclose(file_);
}

std::size_t IfFileStream::read(std::vector<std::byte>& out, std::size_t max_samples) {
  const std::size_t bpw = bytes_per_word(options_.format);
  const std::size_t spw = samples_per_word(options_.format);
  const auto left_words = static_cast<std::size_t>((total_samples_ - next_index_) / static_cast<std::int64_t>(spw));
  const std::size_t wanted = max_samples == 0 ? 0 : std::min(std::max<std::size_t>(max_samples / spw, 1), left_words);
  out.resize(wanted * bpw);
  const std::size_t got = wanted == 0 ? 0 : std::fread(out.data(), bpw, wanted, file_);
  if (got < wanted && std::ferror(file_))
    throw std::runtime_error(
        fmt::format("error reading sample file '{}': {}", options_.path.string(), std::strerror(errno)));
  out.resize(got * bpw);
  next_index_ += static_cast<std::int64_t>(got * spw);
  return got * spw;
}

std::size_t IfFileStream::peek(std::vector<std::byte>& out, std::size_t max_samples) {
  const std::int64_t at = next_index_;
  const std::size_t got = read(out, max_samples);
  position_at(at);
  return got;
}

void IfFileStream::seek(std::int64_t sample_index) {
  if (sample_index < next_index_ || sample_index > total_samples_)
    throw std::invalid_argument(fmt::format("sample file '{}': cannot seek to sample {} (next sample {}, {} in all)",
                                            options_.path.string(), sample_index, next_index_, total_samples_));
  if (const auto spw = static_cast<std::int64_t>(samples_per_word(options_.format)); sample_index % spw != 0)
    throw std::invalid_argument(fmt::format("sample file '{}': cannot seek to sample {}: {} packs {} samples a word",
                                            options_.path.string(), sample_index, to_string(options_.format), spw));
  position_at(sample_index);
}

void IfFileStream::position_at(std::int64_t sample_index) {
  const auto word = sample_index / static_cast<std::int64_t>(samples_per_word(options_.format));
  const auto offset = static_cast<off_t>(options_.header_bytes) +
                      static_cast<off_t>(word) * static_cast<off_t>(bytes_per_word(options_.format));
  if (::fseeko(file_, offset, SEEK_SET) != 0)
    throw std::runtime_error(
        fmt::format("cannot seek in sample file '{}': {}", options_.path.string(), std::strerror(errno)));
  next_index_ = sample_index;
}

}  // namespace deepnav
