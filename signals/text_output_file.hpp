#pragma once
// A text product written through a buffer to an OutputFile (ins/output_file.hpp): it
// appears under its final name only when commit() completes it, a partial file is never
// shared with another process, and a write that fails (a full disk) removes the partial
// file and an earlier run's file of the same name at once, naming the file and the reason.
#include <cstdint>
#include <string>
#include <string_view>

#include "ins/output_file.hpp"

namespace deepnav {

class TextOutputFile {
 public:
  /// Creates the partial file; throws std::runtime_error naming the path if it cannot.
  explicit TextOutputFile(std::string path);

  /// Appends `text` (buffered); throws std::runtime_error naming the file when a write
  /// fails (the file is then failed, see fail()).
  void write(std::string_view text);
  /// Sets aside disk space for `bytes` of text to come (OutputFile::reserve).
  void reserve(std::uint64_t bytes);
  /// Flushes, closes and renames to the final path; throws naming the path on failure.
  void commit();
  /// The file will not be completed: drops the buffer and removes the partial file and an
  /// earlier run's file of the same name (OutputFile::fail).
  void fail() noexcept;
  const std::string& path() const { return path_; }

 private:
  void flush();
  std::string path_;
  OutputFile file_;
  std::string buffer_;
};

}  // namespace deepnav
