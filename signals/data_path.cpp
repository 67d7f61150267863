#include "signals/data_path.hpp"

#include <filesystem>

namespace deepnav {

std::string resolve_path(const std::string& path, const std::string& base_dir, const std::string& search_root) {
  namespace fs = std::filesystem;
  if (fs::path(path).is_absolute()) return path;
  const fs::path from_base = fs::path(base_dir) / path;
  std::error_code ec;  // a path that cannot be asked about (too long) counts as not there
  if (fs::exists(from_base, ec) || search_root.empty()) return from_base.lexically_normal().string();
  const fs::path from_root = fs::path(search_root) / path;
  if (fs::exists(from_root, ec)) return from_root.lexically_normal().string();
  return from_base.lexically_normal().string();  // the existence check names this one
}

std::optional<std::string> missing_file_reason(const std::string& path) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(path, ec);
  if (ec) return "cannot be looked up (" + ec.message() + ")";
  if (!exists) return std::string("does not exist");
  return std::nullopt;
}

}  // namespace deepnav
