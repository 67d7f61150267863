#include "receiver/sources/sample_source.hpp"

namespace deepnav {

bool SampleSource::read_block(SampleBlock& block, std::size_t max_samples) {
  block.samples.resize(max_samples);
  const std::size_t got = read(std::span<Sample>(block.samples));
  block.samples.resize(got);
  block.first_sample_index = next_sample_index() - static_cast<std::int64_t>(got);
  block.magnitude_bits = -1;  // new samples: what was prepared for the old ones is void
  block.planar.clear();
  return got > 0;
}

void SampleSource::report_gap(const SampleGap& gap) {
  lost_samples_ += gap.missing_count;
  if (gap_handler_) gap_handler_(gap);
}

}  // namespace deepnav
