#include "signals/sim/if_file_writer.hpp"

#include <string_view>

namespace deepnav {

IfFileWriter::IfFileWriter(std::filesystem::path path) : file_(std::move(path)) {}

void IfFileWriter::write(std::span<const std::byte> bytes) {
  file_.write(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void IfFileWriter::finish() {
  if (!file_.committed()) file_.commit();
}

}  // namespace deepnav
