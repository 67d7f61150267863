#pragma once
// Writes an IF sample file so that an interrupted run never leaves a file that looks
// complete: bytes go to "<path>.partial", and finish() renames it to <path> once every
// byte is on disk. Destroying the writer without finish() deletes the partial file.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>

namespace deepnav {

class IfFileWriter {
 public:
  /// Creates "<path>.partial"; throws std::runtime_error naming it when it cannot.
  explicit IfFileWriter(std::filesystem::path path);
  ~IfFileWriter();
  IfFileWriter(const IfFileWriter&) = delete;
  IfFileWriter& operator=(const IfFileWriter&) = delete;

  /// Appends bytes; throws std::runtime_error naming the file on a short write.
  void write(std::span<const std::byte> bytes);
  /// Flushes, closes and renames the partial file to the final path (replacing an
  /// existing file); throws std::runtime_error naming the path on failure.
  void finish();

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& partial_path() const { return partial_; }
  std::uint64_t bytes_written() const { return bytes_; }
  bool finished() const { return finished_; }

 private:
  void discard() noexcept;
  std::filesystem::path path_, partial_;
  std::FILE* file_ = nullptr;
  std::uint64_t bytes_ = 0;
  bool finished_ = false;
};

}  // namespace deepnav
