#pragma once
// A recorded IF file as a byte stream: whole samples of the given format (whole words of a
// packed format, several samples each), read in bounded pieces. The one reader of IF files: a server sends its bytes as they are, and the
// receiver's FileSampleSource converts them to samples.
#include <cstdio>
#include <filesystem>
#include <string>

#include "signals/if_byte_stream.hpp"

namespace deepnav {

struct IfFileStreamOptions {
  std::filesystem::path path;
  SampleFormat format = SampleFormat::ibyte;
  double sample_rate_hz = 0.0;
  double if_hz = 0.0;
  std::optional<GpsTime> start_time;  ///< GPS time of the file's first sample, when known
  /// Where the samples are in the file (a recording's header and footer, as a metadata file
  /// describes them): bytes before the first sample, bytes after the last one, and at most
  /// this many bytes of samples.
  std::uint64_t header_bytes = 0;
  std::uint64_t footer_bytes = 0;
  std::optional<std::uint64_t> length_bytes;
};

class IfFileStream final : public IfByteStream {
 public:
  /// Throws std::runtime_error naming the file when it cannot be opened, is empty or holds
  /// no whole sample, std::invalid_argument for a sample rate that is not positive.
  explicit IfFileStream(IfFileStreamOptions options);
  ~IfFileStream() override;
  IfFileStream(const IfFileStream&) = delete;
  IfFileStream& operator=(const IfFileStream&) = delete;

  SampleFormat format() const override { return options_.format; }
  double sample_rate_hz() const override { return options_.sample_rate_hz; }
  double if_hz() const override { return options_.if_hz; }
  std::optional<GpsTime> start_time() const override { return options_.start_time; }
  std::optional<std::int64_t> total_samples() const override { return total_samples_; }
  /// Packed formats: whole words, max_samples rounded down to them but at least one word.
  std::size_t read(std::vector<std::byte>& out, std::size_t max_samples) override;
  /// Packed formats: only to the first sample of a word.
  void seek(std::int64_t sample_index) override;
  std::int64_t next_sample_index() const override { return next_index_; }
  /// The same bytes read() would give, without moving on.
  std::size_t peek(std::vector<std::byte>& out, std::size_t max_samples);
  /// Problems that do not stop reading (a trailing partial sample), one sentence each.
  const std::vector<std::string>& warnings() const { return warnings_; }
  const std::filesystem::path& path() const { return options_.path; }

 private:
  /// Puts the file position at a sample index.
  void position_at(std::int64_t sample_index);
  IfFileStreamOptions options_;
  std::FILE* file_ = nullptr;
  std::int64_t total_samples_ = 0;
  std::int64_t next_index_ = 0;
  std::vector<std::string> warnings_;
};

}  // namespace deepnav
