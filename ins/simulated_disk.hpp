#pragma once
// The output-file layer's fault-injection hook (output_file.hpp), compiled in always so
// that the tests exercise the program as shipped. With DEEPNAV_TEST_DISK_BYTES=N in the
// environment, the files that the process writes through OutputFile behave as if they
// were on a disk with N bytes free: a write (or a reservation) that would take more fails
// with ENOSPC, and a partial file removed or a reservation given back frees its bytes
// again, as on a real full disk. Without the variable nothing is counted or refused.
// docs/testing.md describes its use.
#include <cstdint>
#include <optional>

namespace deepnav::simulated_disk {

/// The name of the environment variable.
inline constexpr const char* kVariable = "DEEPNAV_TEST_DISK_BYTES";

/// Takes `bytes` more of the simulated disk: false (and nothing taken) when they do not
/// fit; always true without the variable. Throws std::runtime_error when the variable is
/// not a byte count.
bool take(std::uint64_t bytes);

/// Gives back `bytes` taken before (a file removed or truncated).
void give_back(std::uint64_t bytes) noexcept;

/// Replaces the environment's setting, for unit tests (which cannot set the variable before
/// the process's first output file): a disk of `capacity` bytes with none used, or none.
void simulate(std::optional<std::uint64_t> capacity);

}  // namespace deepnav::simulated_disk
