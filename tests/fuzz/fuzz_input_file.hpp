#pragma once
// For the readers that take a path, not a stream: the input written to a file of this
// process's own (harnesses run side by side), removed when the process ends.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace deepnav::fuzz {

class InputFile {
 public:
  /// A file named `prefix`, the process id and `extension` in the temporary folder.
  InputFile(const std::string& prefix, const std::string& extension)
      : path_(std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()) + extension)) {}
  ~InputFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Replaces the file's bytes with the input's; returns its path.
  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path_;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace deepnav::fuzz
