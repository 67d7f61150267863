#pragma once
// The last N samples a receiver has seen, for re-acquisition: a ring buffer written with
// block copies (appending to a vector and erasing its front moved every sample twice per
// block), read out in order only when a search runs.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "receiver/sources/sample_source.hpp"

namespace deepnav {

class SampleHistory {
 public:
  explicit SampleHistory(std::size_t capacity) : ring_(capacity) {}

  /// Appends samples[0, n) whose first has absolute index `first_index`; the history must
  /// be contiguous, so call clear() after a gap.
  void append(const Sample* samples, std::size_t n, std::int64_t first_index) {
    end_index_ = first_index + static_cast<std::int64_t>(n);
    const std::size_t cap = ring_.size();
    if (n >= cap) {  // only the last `cap` samples matter
      samples += n - cap;
      n = cap;
    }
    const std::size_t head = std::min(n, cap - write_);
    std::memcpy(ring_.data() + write_, samples, head * sizeof(Sample));
    std::memcpy(ring_.data(), samples + head, (n - head) * sizeof(Sample));
    write_ = (write_ + n) % cap;
    size_ = std::min(cap, size_ + n);
  }
  void clear() { size_ = write_ = 0; }
  bool full() const { return size_ == ring_.size(); }
  std::size_t size() const { return size_; }
  /// Absolute index of the oldest sample held.
  std::int64_t first_index() const { return end_index_ - static_cast<std::int64_t>(size_); }
  /// The samples held, oldest first.
  std::vector<Sample> in_order() const {
    std::vector<Sample> out(size_);
    const std::size_t start = (write_ + ring_.size() - size_) % ring_.size();
    const std::size_t head = std::min(size_, ring_.size() - start);
    std::memcpy(out.data(), ring_.data() + start, head * sizeof(Sample));
    std::memcpy(out.data() + head, ring_.data(), (size_ - head) * sizeof(Sample));
    return out;
  }

 private:
  std::vector<Sample> ring_;
  std::size_t write_ = 0, size_ = 0;
  std::int64_t end_index_ = 0;
};

}  // namespace deepnav
