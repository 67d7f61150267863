#include "signals/sim/synthesized_if_stream.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace deepnav {

SynthesizedIfStream::SynthesizedIfStream(std::shared_ptr<const IfSynthesizer> synthesizer, unsigned threads)
    : synth_(std::move(synthesizer)),
      generator_(synth_->chunk_generator(threads)),
      bytes_per_sample_(bytes_per_word(synth_->scenario().format)) {
  if (is_packed(synth_->scenario().format))
    throw std::invalid_argument("synthesized stream: packed format " + to_string(synth_->scenario().format) +
                                " is written to files only, not streamed");
}

SampleFormat SynthesizedIfStream::format() const { return synth_->scenario().format; }
double SynthesizedIfStream::sample_rate_hz() const { return synth_->scenario().sample_rate_hz; }
double SynthesizedIfStream::if_hz() const { return synth_->scenario().if_hz; }
std::optional<GpsTime> SynthesizedIfStream::start_time() const { return synth_->scenario().start_time; }
std::optional<std::int64_t> SynthesizedIfStream::total_samples() const { return synth_->total_samples(); }

bool SynthesizedIfStream::refill() {
  chunk_offset_ = 0;
  return generator_->next(chunk_);
}

std::size_t SynthesizedIfStream::read(std::vector<std::byte>& out, std::size_t max_samples) {
  // Fills across chunk boundaries, so readers get the sizes they ask for.
  out.clear();
  std::size_t count = 0;
  while (count < max_samples) {
    if (chunk_offset_ >= chunk_.size() && !refill()) break;
    const std::size_t available = (chunk_.size() - chunk_offset_) / bytes_per_sample_;
    const std::size_t n = std::min(available, max_samples - count);
    const auto first = chunk_.begin() + static_cast<std::ptrdiff_t>(chunk_offset_);
    out.insert(out.end(), first, first + static_cast<std::ptrdiff_t>(n * bytes_per_sample_));
    chunk_offset_ += n * bytes_per_sample_;
    count += n;
  }
  next_index_ += static_cast<std::int64_t>(count);
  return count;
}

void SynthesizedIfStream::seek(std::int64_t sample_index) {
  if (sample_index < next_index_ || sample_index > synth_->total_samples())
    throw std::invalid_argument(fmt::format("synthesized stream: cannot seek to sample {} (next sample {}, {} in all)",
                                            sample_index, next_index_, synth_->total_samples()));
  std::vector<std::byte> discard;
  while (next_index_ < sample_index) {
    if (read(discard, static_cast<std::size_t>(sample_index - next_index_)) == 0) break;
  }
}

}  // namespace deepnav
