#include "signals/text_output_file.hpp"

namespace deepnav {
namespace {

/// Text is handed to the file in blocks of this size (a product writes a line at a time).
constexpr std::size_t kBufferBytes = 64 * 1024;

}  // namespace

TextOutputFile::TextOutputFile(std::string path) : path_(std::move(path)), file_(path_) {}

void TextOutputFile::write(std::string_view text) {
  buffer_.append(text);
  if (buffer_.size() >= kBufferBytes) flush();
}

void TextOutputFile::flush() {
  if (buffer_.empty()) return;
  std::string block;
  block.swap(buffer_);  // emptied even when the write throws: a failed file takes no more text
  file_.write(block);
  block.clear();
  buffer_.swap(block);  // keeps the allocation for the next block
}

void TextOutputFile::reserve(std::uint64_t bytes) { file_.reserve(bytes); }

void TextOutputFile::commit() {
  flush();
  file_.commit();
}

void TextOutputFile::fail() noexcept {
  buffer_.clear();
  file_.fail();
}

}  // namespace deepnav
