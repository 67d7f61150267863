#pragma once
// Runs a body over [0, total) split into contiguous ranges, one per worker thread (the
// calling thread takes the first range). What the synthesizer parallelises: the epoch
// boundaries, the satellites' signals and the thermal noise, each of whose values depend
// only on their index, so any split gives the same samples.
#include <functional>

namespace deepnav {

/// Worker threads `threads` stands for: 0 means one per core.
unsigned resolved_threads(unsigned threads);
/// How many workers run_in_ranges uses for `total` items: min(threads, total), at least 1.
int range_workers(unsigned threads, int total);
/// Where worker w of `workers` starts: total * w / workers (worker w ends where w + 1 starts).
inline int range_begin(int total, int workers, int w) {
  return static_cast<int>(static_cast<long long>(total) * w / workers);
}

/// body(worker, begin, end) for worker w in [0, range_workers(threads, total)), over
/// [range_begin(w), range_begin(w + 1)). A worker's exception, or a thread that cannot be started
/// (std::runtime_error naming it), is rethrown once every started worker has been joined.
void run_in_ranges(unsigned threads, int total, const std::function<void(int worker, int begin, int end)>& body);

}  // namespace deepnav
