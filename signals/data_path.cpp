#include "signals/data_path.hpp"

#include <filesystem>

namespace deepnav {

std::string resolve_path(const std::string& path, const std::string& base_dir, const std::string& search_root) {
  namespace fs = std::filesystem;
  if (fs::path(path).is_absolute()) return path;
  const fs::path from_base = fs::path(base_dir) / path;
  if (fs::exists(from_base) || search_root.empty()) return from_base.lexically_normal().string();
  const fs::path from_root = fs::path(search_root) / path;
  if (fs::exists(from_root)) return from_root.lexically_normal().string();
  return from_base.lexically_normal().string();  // the existence check names this one
}

}  // namespace deepnav
