#pragma once
// A scenario synthesized on the fly, as a byte stream: the same bytes, in the same order,
// as the IF file `deepnav sim` writes (jammers, noise, AGC and ADC included), produced one
// chunk (100 ms) at a time so a stream of any length needs a few MB of memory.
#include <memory>

#include "signals/if_byte_stream.hpp"
#include "signals/sim/if_synthesizer.hpp"

namespace deepnav {

class SynthesizedIfStream final : public IfByteStream {
 public:
  /// `synthesizer` may be shared by several streams (each generates from sample 0).
  SynthesizedIfStream(std::shared_ptr<const IfSynthesizer> synthesizer, unsigned threads);

  SampleFormat format() const override;
  double sample_rate_hz() const override;
  double if_hz() const override;
  std::optional<GpsTime> start_time() const override;
  std::optional<std::int64_t> total_samples() const override;
  std::size_t read(std::vector<std::byte>& out, std::size_t max_samples) override;
  /// Forward seeks generate and discard the samples in between (the front end's AGC and
  /// noise are sequential, so there is no shortcut that keeps the bytes identical).
  void seek(std::int64_t sample_index) override;
  std::int64_t next_sample_index() const override { return next_index_; }

 private:
  bool refill();

  std::shared_ptr<const IfSynthesizer> synth_;
  std::unique_ptr<IfChunkGenerator> generator_;
  std::size_t bytes_per_sample_;
  std::vector<std::byte> chunk_;
  std::size_t chunk_offset_ = 0;  ///< bytes of chunk_ already delivered
  std::int64_t next_index_ = 0;
};

}  // namespace deepnav
