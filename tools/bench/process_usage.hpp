#pragma once
// What this process has used: CPU time (all threads, or the calling thread alone), peak
// resident memory and wall time since a start. The benchmarks report these, and every
// run writes them into its summary, so memory growth with run length can be checked.
#include <chrono>

namespace deepnav::bench {

/// CPU seconds the process has used, every thread together (user + system).
double process_cpu_s();
/// CPU seconds of the calling thread.
double thread_cpu_s();
/// The largest resident set the process has had so far (MiB).
double peak_rss_mib();
/// Wall seconds since `t0`.
double seconds_since(std::chrono::steady_clock::time_point t0);

}  // namespace deepnav::bench
