#include "signals/sim/if_file_writer.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace deepnav {
namespace {

constexpr std::size_t kBufferBytes = 1 << 20;  // large writes: the synthesizer emits ms blocks

std::runtime_error io_error(const std::string& what, const std::filesystem::path& path, int err) {
  return std::runtime_error(what + " '" + path.string() + "': " + std::strerror(err));
}

}  // namespace

IfFileWriter::IfFileWriter(std::filesystem::path path) : path_(std::move(path)) {
  partial_ = path_;
  partial_ += ".partial";
  file_ = std::fopen(partial_.c_str(), "wb");
  if (!file_) throw io_error("cannot create IF sample file", partial_, errno);
  std::setvbuf(file_, nullptr, _IOFBF, kBufferBytes);
}

IfFileWriter::~IfFileWriter() {
  if (!finished_) discard();
}

void IfFileWriter::discard() noexcept {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  std::error_code ignored;
  std::filesystem::remove(partial_, ignored);
}

void IfFileWriter::write(std::span<const std::byte> bytes) {
  if (!file_) throw std::runtime_error("IF sample file '" + path_.string() + "' is already closed");
  if (bytes.empty()) return;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw io_error("cannot write IF sample file", partial_, errno);
  bytes_ += bytes.size();
}

void IfFileWriter::finish() {
  if (finished_) return;
  if (!file_) throw std::runtime_error("IF sample file '" + path_.string() + "' is already closed");
  const bool flushed = std::fflush(file_) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    const int err = !flushed ? flush_errno : errno;
    discard();
    throw io_error("cannot finish IF sample file", partial_, err);
  }
  std::error_code ec;
  std::filesystem::rename(partial_, path_, ec);
  if (ec) {
    discard();
    throw std::runtime_error("cannot rename '" + partial_.string() + "' to '" + path_.string() + "': " + ec.message());
  }
  finished_ = true;
}

}  // namespace deepnav
