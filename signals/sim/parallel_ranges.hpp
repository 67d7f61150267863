#pragma once
// Runs a body over [0, total) split into contiguous ranges, one per worker thread (the
// calling thread takes the first range). What the synthesizer parallelises: the epoch
// boundaries, the satellites' signals and the thermal noise, each of whose values depend
// only on their index, so any split gives the same samples.
#include <functional>

namespace deepnav {

/// body(worker, begin, end) for worker w in [0, workers): ranges [total*w/W, total*(w+1)/W)
/// with W = min(threads, total). A worker's exception, or a thread that cannot be started
/// (std::runtime_error naming it), is rethrown once every started worker has been joined.
void run_in_ranges(unsigned threads, int total, const std::function<void(int worker, int begin, int end)>& body);

}  // namespace deepnav
