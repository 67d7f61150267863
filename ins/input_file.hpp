#pragma once
// What every file reader checks before it opens an input: that the path names a regular
// file (not a directory, a FIFO that would block until a writer comes, or a device such as
// /dev/zero that never ends) and, for text inputs, that it is not absurdly large.
#include <cstdint>
#include <string>

namespace deepnav {

/// Throws std::runtime_error "<what> 'path': ..." naming the problem when `path` does not
/// exist, is not a regular file, or is larger than max_bytes (0: no limit).
void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes = 0);

/// The size limit of text inputs (configuration, scenario, CSV and navigation files).
inline constexpr std::uintmax_t kMaxTextInputBytes = std::uintmax_t{1} << 30;

}  // namespace deepnav
