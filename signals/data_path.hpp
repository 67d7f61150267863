#pragma once
// Where a relative path in a file or an option names a file: beside the file that names
// it, else under the project's root (so `data/brdc0010.22n` and the default IMU grades
// resolve from any working directory).
#include <optional>
#include <string>

namespace deepnav {

/// `path` if absolute; else base_dir/path if it exists (or no search_root is given); else
/// search_root/path if that exists; else base_dir/path (for the caller's "does not exist").
std::string resolve_path(const std::string& path, const std::string& base_dir, const std::string& search_root);

/// Why `path` names no file to read: "does not exist", or what the system said when asking
/// (a name too long, a component that is not a folder); nullopt when it exists. Never
/// throws: a path written in a file is input, and any text is a possible path.
std::optional<std::string> missing_file_reason(const std::string& path);

}  // namespace deepnav
