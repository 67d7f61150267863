#include "tools/cli/output_folder.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "ins/output_file.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
namespace fs = std::filesystem;
namespace {

void refuse_replacing_inputs(const std::string& dir, const std::vector<std::string>& product_names,
                             const std::vector<NamedInput>& inputs) {
  for (const NamedInput& input : inputs) {
    if (input.path.empty()) continue;
    for (const std::string& name : product_names) {
      std::error_code ec;  // a product not there yet (or an input that is not a file) is no clash
      if (!fs::equivalent(fs::path(dir) / name, input.path, ec) || ec) continue;
      throw UserError(fmt::format(
          "--out '{}': its product {} would replace the input '{}' ({}): choose another --out folder or move the "
          "input out of it",
          dir, name, input.path, input.option));
    }
  }
}

/// The partial files of `product_names` in `dir` that no process writes any more.
void remove_leftover_partial_files(const std::string& dir, const std::vector<std::string>& product_names) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string file_name = entry.path().filename().string();
    for (const std::string& product : product_names) {
      if (!is_partial_file_of(file_name, product)) continue;
      std::error_code removed;
      if (fs::remove(entry.path(), removed))
        spdlog::info("removed '{}', left by a run that was killed", entry.path().string());
      break;
    }
  }
}

}  // namespace

std::vector<NamedInput> config_file_input(CLI::App& root) {
  const CLI::Option* config = root.get_config_ptr();
  if (config == nullptr || config->results().empty()) return {};
  return {{"--config", config->results().front()}};
}

OutputFolder::OutputFolder(std::string dir, const std::vector<std::string>& product_names,
                           const std::vector<NamedInput>& inputs)
    : dir_(std::move(dir)) {
  refuse_replacing_inputs(dir_, product_names, inputs);
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw UserError(fmt::format("cannot create output folder '{}': {}", dir_, ec.message()));
  lock_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0) throw UserError(fmt::format("cannot open output folder '{}': {}", dir_, std::strerror(errno)));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) == 0) {
    remove_leftover_partial_files(dir_, product_names);
    return;
  }
  const int error = errno;
  if (error == EWOULDBLOCK) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw UserError(fmt::format(
        "output folder '{}' is in use: another deepnav process is writing its products there; wait for it to end or "
        "choose another --out",
        dir_));
  }
  // A file system without locks (some network mounts): the partial files are still this
  // process's own, only the final names would be the last writer's.
  spdlog::warn("cannot lock output folder '{}' ({}): a second process writing into it would not be refused", dir_,
               std::strerror(error));
}

OutputFolder::~OutputFolder() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

std::string OutputFolder::path(std::string_view name) const { return (fs::path(dir_) / name).string(); }

}  // namespace deepnav::cli
