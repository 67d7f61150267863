#pragma once
// An output file that appears under its final name only when it is complete: it is
// written as `<path>.partial` and renamed by commit(). If the run fails before that,
// the destructor removes the partial file, so nothing incomplete passes for a result.
#include <fstream>
#include <string>
#include <string_view>

namespace deepnav {

class TextOutputFile {
 public:
  /// Opens `<path>.partial`; throws std::runtime_error naming the path if it cannot.
  explicit TextOutputFile(std::string path);
  ~TextOutputFile();
  TextOutputFile(const TextOutputFile&) = delete;
  TextOutputFile& operator=(const TextOutputFile&) = delete;

  void write(std::string_view text);
  /// Flushes, closes and renames to the final path; throws naming the path on failure.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string partial_path_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace deepnav
