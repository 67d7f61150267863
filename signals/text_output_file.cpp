#include "signals/text_output_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace deepnav {

TextOutputFile::TextOutputFile(std::string path) : path_(std::move(path)), partial_path_(path_ + ".partial") {
  out_.open(partial_path_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    throw std::runtime_error("cannot write '" + partial_path_ + "': " + std::strerror(errno));
  }
}

TextOutputFile::~TextOutputFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(partial_path_, ec);
  }
}

void TextOutputFile::write(std::string_view text) {
  out_.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out_) throw std::runtime_error("write to '" + partial_path_ + "' failed (disk full?)");
}

void TextOutputFile::commit() {
  out_.flush();
  out_.close();
  if (!out_) throw std::runtime_error("closing '" + partial_path_ + "' failed (disk full?)");
  std::error_code ec;
  std::filesystem::rename(partial_path_, path_, ec);
  if (ec) throw std::runtime_error("cannot rename '" + partial_path_ + "' to '" + path_ + "': " + ec.message());
  committed_ = true;
}

}  // namespace deepnav
