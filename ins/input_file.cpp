#include "ins/input_file.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace deepnav {

void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw std::runtime_error(fmt::format("cannot open {} '{}': {}", what, path, std::strerror(errno)));
  const char* kind = nullptr;
  if (S_ISDIR(st.st_mode)) kind = "a directory";
  else if (S_ISFIFO(st.st_mode)) kind = "a FIFO (it would block until a writer comes)";
  else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) kind = "a device";
  else if (S_ISSOCK(st.st_mode)) kind = "a socket";
  else if (!S_ISREG(st.st_mode)) kind = "not a regular file";
  if (kind != nullptr)
    throw std::runtime_error(fmt::format("{} '{}' is {}, expected a regular file", what, path, kind));
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (max_bytes != 0 && size > max_bytes)
    throw std::runtime_error(fmt::format("{} '{}' is {} bytes, more than the {} bytes such a file can sensibly hold",
                                         what, path, size, max_bytes));
}

}  // namespace deepnav
