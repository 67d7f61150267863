#pragma once
// Writes an IF sample file so that an interrupted run never leaves a file that looks
// complete: the bytes go to a partial file of this process's own (ins/output_file.hpp),
// and finish() renames it to <path> once every byte is on disk. Destroying the writer
// without finish() deletes the partial file; a write that fails deletes it at once.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

#include "ins/output_file.hpp"

namespace deepnav {

class IfFileWriter {
 public:
  /// Creates the partial file; throws std::runtime_error naming it when it cannot.
  explicit IfFileWriter(std::filesystem::path path);

  /// Appends bytes (the synthesizer hands over 100 ms blocks: no buffer of its own);
  /// throws std::runtime_error naming the file and the reason when they cannot be written.
  void write(std::span<const std::byte> bytes);
  /// Closes and renames the partial file to the final path (replacing an existing file);
  /// throws std::runtime_error naming the path on failure.
  void finish();

  const std::filesystem::path& path() const { return file_.path(); }
  const std::filesystem::path& partial_path() const { return file_.partial_path(); }
  std::uint64_t bytes_written() const { return file_.bytes_written(); }
  bool finished() const { return file_.committed(); }

 private:
  OutputFile file_;
};

}  // namespace deepnav
