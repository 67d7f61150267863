#include "ins/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "ins/simulated_disk.hpp"

namespace deepnav {
namespace {

/// Partial names tried after "<path>.<pid>.partial" is taken (the same product opened
/// twice by one process, or a leftover of a killed process that had the same pid).
constexpr int kMaxPartialSuffix = 100;

/// A symbolic link's final target (itself when it is none, or dangling).
std::filesystem::path link_target(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return path;
  std::error_code ec;
  std::filesystem::path target = std::filesystem::canonical(path, ec);
  return ec ? path : target;
}

}  // namespace

OutputFile::OutputFile(std::filesystem::path path) : path_(std::move(path)), target_(link_target(path_)) {
  simulated_disk::take(0);  // a malformed hook setting is an error before anything is written
  struct stat st {};
  if (::stat(target_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw std::runtime_error(fmt::format("cannot write '{}': it is a folder", path_.string()));
    fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error(fmt::format("cannot write '{}': {}", path_.string(), std::strerror(errno)));
    in_place_ = true;
    partial_ = target_;
    return;
  }
  open_partial();
}

void OutputFile::open_partial() {
  const std::string stem = fmt::format("{}.{}", target_.string(), ::getpid());
  for (int k = 0;; ++k) {
    partial_ = k == 0 ? stem + ".partial" : fmt::format("{}-{}.partial", stem, k);
    // O_EXCL: never an existing file, nor a link planted under the name.
    fd_ = ::open(partial_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ >= 0) return;
    if (errno != EEXIST || k == kMaxPartialSuffix)
      throw std::runtime_error(fmt::format("cannot create '{}': {}", partial_.string(), std::strerror(errno)));
  }
}

OutputFile::~OutputFile() {
  if (state_ != State::writing) return;
  ::close(fd_);
  if (in_place_) return;
  ::unlink(partial_.c_str());
  simulated_disk::give_back(allocated_);
}

void OutputFile::require_writing(const char* what) const {
  if (state_ != State::writing)
    throw std::logic_error(fmt::format("cannot {} '{}': it is already {}", what, path_.string(),
                                       state_ == State::committed ? "complete" : "abandoned after an error"));
}

void OutputFile::fail_with(const char* what, int error) {
  fail();
  throw std::runtime_error(fmt::format("{} '{}': {}{}", what, path_.string(), std::strerror(error),
                                       removed_earlier_ ? " (an earlier run's file of that name is removed)" : ""));
}

void OutputFile::write(std::string_view bytes) {
  require_writing("write");
  if (!in_place_ && written_ + bytes.size() > allocated_) {
    const std::uint64_t more = written_ + bytes.size() - allocated_;
    if (!simulated_disk::take(more)) fail_with("cannot write", ENOSPC);
    allocated_ += more;
  }
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      fail_with("cannot write", errno);
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
    written_ += static_cast<std::uint64_t>(n);
  }
}

void OutputFile::reserve(std::uint64_t bytes) {
  require_writing("reserve space for");
  if (in_place_ || bytes <= allocated_) return;
  const std::uint64_t more = bytes - allocated_;
  const auto refuse = [&](int error) {
    return std::runtime_error(
        fmt::format("cannot reserve {} bytes for '{}': {}", bytes, path_.string(), std::strerror(error)));
  };
  if (!simulated_disk::take(more)) throw refuse(ENOSPC);
  // Allocated from the start: the writes to come overwrite it, commit() cuts what is left.
  if (const int error = ::posix_fallocate(fd_, 0, static_cast<off_t>(bytes)); error != 0) {
    simulated_disk::give_back(more);
    throw refuse(error);
  }
  allocated_ = bytes;
  reserved_ = bytes;
}

void OutputFile::commit() {
  require_writing("finish");
  if (reserved_ > written_) {
    if (::ftruncate(fd_, static_cast<off_t>(written_)) != 0) fail_with("cannot finish", errno);
    simulated_disk::give_back(allocated_ - written_);
    allocated_ = written_;
  }
  // close() reports what a delayed write could not store (NFS, a quota); the descriptor is
  // released either way.
  if (::close(std::exchange(fd_, -1)) != 0) fail_with("cannot finish", errno);
  if (!in_place_ && ::rename(partial_.c_str(), target_.c_str()) != 0) {
    const int error = errno;
    fail();
    throw std::runtime_error(
        fmt::format("cannot rename '{}' to '{}': {}", partial_.string(), target_.string(), std::strerror(error)));
  }
  state_ = State::committed;
}

void OutputFile::fail() noexcept {
  if (state_ != State::writing) return;
  state_ = State::failed;
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
  if (in_place_) return;
  ::unlink(partial_.c_str());
  simulated_disk::give_back(std::exchange(allocated_, 0));
  struct stat st {};
  if (::lstat(target_.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::unlink(target_.c_str()) == 0)
    removed_earlier_ = true;
}

bool is_partial_file_of(std::string_view file_name, std::string_view product_name) {
  constexpr std::string_view kSuffix = ".partial";
  if (file_name.size() < product_name.size() + kSuffix.size() || !file_name.starts_with(product_name) ||
      !file_name.ends_with(kSuffix))
    return false;
  // What lies between: nothing, or ".<pid>" or ".<pid>-<k>" (open_partial()).
  std::string_view middle = file_name.substr(product_name.size());
  middle.remove_suffix(kSuffix.size());
  if (middle.empty()) return true;
  if (middle.front() != '.') return false;
  middle.remove_prefix(1);
  const auto digits = [](std::string_view text) {
    return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
  };
  const std::size_t dash = middle.find('-');
  if (dash == std::string_view::npos) return digits(middle);
  return digits(middle.substr(0, dash)) && digits(middle.substr(dash + 1));
}

}  // namespace deepnav
