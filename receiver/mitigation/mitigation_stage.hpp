#pragma once
// One step of the receiver's interference mitigation: a streaming filter over complex
// samples (in the source's sample units) whose output is its input delayed by a fixed
// number of samples, so absolute sample indices survive the chain unchanged.
#include <complex>
#include <cstddef>
#include <span>

namespace deepnav {

class MitigationStage {
 public:
  virtual ~MitigationStage() = default;
  /// Output sample k is the filtered input sample k - delay_samples() (zeros before the start).
  virtual std::size_t delay_samples() const = 0;
  /// Consumes `in` and writes in.size() output samples to `out`; in and out may be the same span.
  virtual void process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) = 0;
  /// Forgets the past (after a gap in the input): the next sample starts a new stream.
  virtual void reset() = 0;
};

}  // namespace deepnav
