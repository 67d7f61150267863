#pragma once
// An output file that takes its final name only when it is complete, written by one
// process alone. The bytes go to "<path>.<pid>.partial" beside it, created exclusively, so
// that two processes writing the same product into one folder never share (and splice) a
// partial file; commit() renames it to the final name. When it cannot be completed:
//   - destroyed before commit() (the run stopped on an error): the partial file is
//     removed, and a file of an earlier run under the final name is left as it was;
//   - a write, or the commit, fails (a full disk): fail() at once, which removes the
//     partial file (its space goes back to the process's other files) and also a file of
//     an earlier run under the final name, which this one can no longer replace and which
//     must not pass for its result; the error names the file and the system's reason.
// An existing path that is not a regular file (a device such as /dev/full, a FIFO, a
// terminal) is written in place, and a symbolic link is followed: its target is replaced.
// Every OutputFile is subject to the fault-injection hook of simulated_disk.hpp.
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace deepnav {

class OutputFile {
 public:
  /// Creates the partial file (or opens a special file in place); throws
  /// std::runtime_error naming the path and the reason when it cannot.
  explicit OutputFile(std::filesystem::path path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Writes every byte (unbuffered); on failure fail()s and throws std::runtime_error
  /// naming the file and the reason.
  void write(std::string_view bytes);
  /// Sets aside disk space for `bytes` of content to come (a product that must survive a
  /// disk filled by the others); throws std::runtime_error naming the file when the space
  /// is not there, the file staying usable without the reservation.
  void reserve(std::uint64_t bytes);
  /// Gives back the unused reservation, closes, and renames to the final path; on failure
  /// fail()s and throws std::runtime_error naming the file and the reason.
  void commit();
  /// The file cannot be completed: removes the partial file and an earlier run's file
  /// under the final name (see above). Does nothing once committed or failed.
  void fail() noexcept;

  /// The final path as given.
  const std::filesystem::path& path() const { return path_; }
  /// Where the bytes go until commit() (the final path itself when written in place).
  const std::filesystem::path& partial_path() const { return partial_; }
  std::uint64_t bytes_written() const { return written_; }
  bool committed() const { return state_ == State::committed; }
  bool failed() const { return state_ == State::failed; }

 private:
  enum class State { writing, committed, failed };
  void open_partial();
  [[noreturn]] void fail_with(const char* what, int error);
  void require_writing(const char* what) const;
  std::filesystem::path path_;    ///< as given
  std::filesystem::path target_;  ///< what commit() replaces (a symbolic link's target)
  std::filesystem::path partial_;
  int fd_ = -1;
  bool in_place_ = false;
  State state_ = State::writing;
  std::uint64_t written_ = 0;
  std::uint64_t reserved_ = 0;   ///< reserve()d, up to which the file is allocated
  std::uint64_t allocated_ = 0;  ///< taken from the simulated disk (simulated_disk.hpp)
  bool removed_earlier_ = false;
};

/// Whether `file_name` is the name of a partial file an OutputFile makes for a product
/// named `product_name` in the same folder (any process's; also the "<name>.partial" of
/// earlier versions): a leftover of a process killed outright, once none writes there.
bool is_partial_file_of(std::string_view file_name, std::string_view product_name);

}  // namespace deepnav
