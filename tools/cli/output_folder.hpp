#pragma once
// The folder a command writes its products into (`--out` of run, fuse and sim), held while
// the command runs. Before anything is written, a product that would replace one of the
// command's own inputs (fuse's obs.rnx, sim's scenario.yaml in their own folder) is refused
// naming both; then the folder is created if missing and locked, so that a second deepnav
// process writing into it is refused at once instead of mixing its products with the
// first's. The lock is flock(2) on the folder itself: nothing is left on disk, and it ends
// with the process however that ends. Holding it, the command removes the partial files of
// its products that a process killed outright (SIGKILL, a power cut) left there. (The
// benchmarks' sweep folders are shared by design, each point writing its own files, and
// are not locked.)
#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace deepnav::cli {

/// One of a command's input files, and the option that named it.
struct NamedInput {
  std::string option;
  std::string path;  ///< empty: not given (skipped)
};

/// The --config file, when one was given to the root app.
std::vector<NamedInput> config_file_input(CLI::App& root);

class OutputFolder {
 public:
  /// Throws UserError when a product (`product_names` in `dir`) is the same file as one of
  /// `inputs` (naming both), when `dir` cannot be created, or when another process holds
  /// it; then removes the products' leftover partial files.
  OutputFolder(std::string dir, const std::vector<std::string>& product_names, const std::vector<NamedInput>& inputs);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::string& dir() const { return dir_; }
  /// `name` in the folder.
  std::string path(std::string_view name) const;

 private:
  std::string dir_;
  int lock_fd_ = -1;
};

}  // namespace deepnav::cli
