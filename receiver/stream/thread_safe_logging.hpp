#pragma once
// Network sources and the stream server log from their I/O threads, and spdlog's default
// logger (single-threaded, set up by the command line) must not be shared across threads.

namespace deepnav {

/// Replaces the default logger by a thread-safe one with the same sink (stderr), pattern and
/// level; later calls do nothing.
void use_thread_safe_logger();

}  // namespace deepnav
