#pragma once
// IF samples as bytes in one of the sample formats, read in order from the first sample:
// what a streaming server sends. Implementations: a recorded file (IfFileStream) and
// the synthesizer generating a scenario on the fly (SynthesizedIfStream).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "ins/gps_time.hpp"
#include "signals/sample_format.hpp"

namespace deepnav {

class IfByteStream {
 public:
  virtual ~IfByteStream() = default;

  virtual SampleFormat format() const = 0;
  virtual double sample_rate_hz() const = 0;
  virtual double if_hz() const = 0;
  /// GPS time (receiver clock) of sample 0, when the source knows it.
  virtual std::optional<GpsTime> start_time() const = 0;
  /// Samples in the whole stream, when known in advance.
  virtual std::optional<std::int64_t> total_samples() const = 0;

  /// Replaces `out` with the bytes of up to `max_samples` whole samples that follow the
  /// last ones read; returns the sample count (0 only at the end of the stream).
  virtual std::size_t read(std::vector<std::byte>& out, std::size_t max_samples) = 0;
  /// Moves forward so that the next sample read is `sample_index` (never backwards);
  /// throws std::invalid_argument for an index behind the current one or past the end.
  virtual void seek(std::int64_t sample_index) = 0;
  /// Absolute index of the next sample read() delivers.
  virtual std::int64_t next_sample_index() const = 0;
};

}  // namespace deepnav
