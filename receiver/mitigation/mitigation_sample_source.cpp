#include "receiver/mitigation/mitigation_sample_source.hpp"

#include <algorithm>
#include <cmath>

#include "receiver/mitigation/mitigation_blanking.hpp"
#include "receiver/mitigation/mitigation_excision.hpp"
#include "receiver/mitigation/mitigation_notch.hpp"

namespace deepnav {
namespace {

/// Samples read from the wrapped source at a time.
constexpr std::size_t kPieceSamples = 16384;
/// Samples whose RMS sets the output gain.
constexpr std::size_t kGainSamples = 4096;
/// RMS (int16 units) that the floating-point filters' output is held at; 24 dB below
/// full scale, as FileSampleSource scales float files.
constexpr double kTargetRms = 2048.0;
/// The output level control: power measured over windows of this many samples ...
constexpr int kLevelWindow = 64;
/// ... and smoothed with this time constant (the same as a typical front-end AGC).
constexpr double kLevelTimeConstantS = 0.01;

std::int16_t saturate_int16(float v) {
  return static_cast<std::int16_t>(std::clamp(std::nearbyint(v), -32768.0f, 32767.0f));
}

}  // namespace

MitigationSampleSource::MitigationSampleSource(SampleSource& inner, const MitigationConfig& config)
    : inner_(inner), config_(config) {
  validate_mitigation(config, inner.sample_rate_hz());
  const double fs = inner.sample_rate_hz();
  switch (config.mode) {
    case MitigationMode::none:
      break;
    case MitigationMode::notch:
      stages_.push_back(std::make_unique<AdaptiveNotch>(config, fs));
      break;
    case MitigationMode::excision:
      stages_.push_back(std::make_unique<FrequencyExcision>(config, fs));
      break;
    case MitigationMode::blanking:
      stages_.push_back(std::make_unique<PulseBlanker>(config, fs));
      break;
    case MitigationMode::automatic:
      // Pulses first: a pulse spreads over every bin of the frame it falls in and would
      // defeat the excision's noise floor.
      stages_.push_back(std::make_unique<PulseBlanker>(config, fs));
      stages_.push_back(std::make_unique<FrequencyExcision>(config, fs));
      break;
  }
  // Blanking alone only zeroes samples and passes the others bit-exact.
  normalize_ = !stages_.empty() && config.mode != MitigationMode::blanking;
  next_index_ = inner.next_sample_index();
  to_drop_ = total_delay();
}

MitigationSampleSource::~MitigationSampleSource() = default;

std::size_t MitigationSampleSource::total_delay() const {
  std::size_t d = 0;
  for (const auto& s : stages_) d += s->delay_samples();
  return d;
}

std::size_t MitigationSampleSource::read_through(std::span<Sample> out) {
  const std::size_t got = inner_.read(out);
  if (got == 0) {
    at_end_ = true;
    return 0;
  }
  const std::int64_t first = inner_.next_sample_index() - static_cast<std::int64_t>(got);
  if (first > next_index_) report_gap({next_index_, first - next_index_});
  next_index_ = first + static_cast<std::int64_t>(got);
  return got;
}

std::size_t MitigationSampleSource::read(std::span<Sample> out) {
  if (stages_.empty()) return read_through(out);
  if (out.empty() || at_end_) return 0;
  while (queue_.empty() || queue_.front().delivered == queue_.front().samples.size()) {
    if (!queue_.empty()) queue_.pop_front();
    if (queue_.empty()) {
      if (inner_done_) {
        at_end_ = true;
        return 0;
      }
      pull();
    }
  }
  Segment& seg = queue_.front();
  const std::int64_t seg_index = seg.first_index + static_cast<std::int64_t>(seg.delivered);
  if (seg_index > next_index_) report_gap({next_index_, seg_index - next_index_});
  const std::size_t n = std::min(out.size(), seg.samples.size() - seg.delivered);
  std::copy_n(seg.samples.begin() + static_cast<std::ptrdiff_t>(seg.delivered), n, out.begin());
  seg.delivered += n;
  next_index_ = seg_index + static_cast<std::int64_t>(n);
  return n;
}

bool MitigationSampleSource::take_piece(std::vector<Sample>& dest, std::int64_t& first) {
  if (has_held_) {
    dest.swap(held_);
    first = held_first_;
    has_held_ = false;
    return true;
  }
  if (inner_eof_) return false;
  dest.resize(kPieceSamples);
  const std::size_t got = inner_.read(std::span<Sample>(dest));
  if (got == 0) {
    inner_eof_ = true;
    return false;
  }
  dest.resize(got);
  first = inner_.next_sample_index() - static_cast<std::int64_t>(got);
  return true;
}

void MitigationSampleSource::pull() {
  std::int64_t first = 0;
  if (!take_piece(raw_, first)) {
    flush();
    inner_done_ = true;
    return;
  }
  // Until the level is set, gather enough contiguous samples for it to see kGainSamples
  // filtered ones, so that it (and every output) does not depend on how the wrapped
  // source cuts its reads.
  while (!level_set_ && raw_.size() < kGainSamples + total_delay()) {
    std::int64_t next_first = 0;
    if (!take_piece(piece_, next_first)) break;
    if (next_first != first + static_cast<std::int64_t>(raw_.size())) {
      held_.swap(piece_);
      held_first_ = next_first;
      has_held_ = true;
      break;
    }
    raw_.insert(raw_.end(), piece_.begin(), piece_.end());
  }
  const std::size_t got = raw_.size();
  if (next_input_index_ < 0 || first != next_input_index_) {
    flush();  // the samples before a gap leave the filters as they are
    for (auto& s : stages_) s->reset();
    to_drop_ = total_delay();
    next_output_index_ = first;
  }
  next_input_index_ = first + static_cast<std::int64_t>(got);
  work_.resize(got);
  for (std::size_t k = 0; k < got; ++k)
    work_[k] = {static_cast<float>(raw_[k].real()), static_cast<float>(raw_[k].imag())};
  filter_into_queue(got);
}

void MitigationSampleSource::flush() {
  const std::size_t delay = total_delay();
  if (next_input_index_ < 0 || delay == 0) return;
  work_.assign(delay, {});
  filter_into_queue(delay);
}

void MitigationSampleSource::filter_into_queue(std::size_t count) {
  const std::span<std::complex<float>> w(work_.data(), count);
  for (auto& s : stages_) s->process(w, w);
  const std::size_t skip = std::min(to_drop_, count);
  if (normalize_) {
    if (!level_set_ && skip < count) set_level(w.subspan(skip, std::min(count - skip, kGainSamples)));
    hold_level(w);
  }
  to_drop_ -= skip;
  if (skip == count) return;
  Segment& seg = queue_.emplace_back();
  seg.first_index = next_output_index_;
  seg.samples.reserve(count - skip);
  for (std::size_t k = skip; k < count; ++k)
    seg.samples.emplace_back(saturate_int16(w[k].real()), saturate_int16(w[k].imag()));
  next_output_index_ += static_cast<std::int64_t>(count - skip);
}

void MitigationSampleSource::set_level(std::span<const std::complex<float>> first) {
  level_set_ = true;
  double sum = 0.0;
  for (const auto& x : first) sum += std::norm(x);
  level_power_ = sum / static_cast<double>(first.size());
  gain_ = level_power_ > 0.0 ? static_cast<float>(kTargetRms / std::sqrt(level_power_)) : 1.0f;
}

void MitigationSampleSource::hold_level(std::span<std::complex<float>> w) {
  const double alpha = -std::expm1(-kLevelWindow / (kLevelTimeConstantS * inner_.sample_rate_hz()));
  for (auto& x : w) {
    window_power_ += std::norm(x);
    x *= gain_;
    if (++window_count_ == kLevelWindow) {
      level_power_ += alpha * (window_power_ / kLevelWindow - level_power_);
      if (level_power_ > 0.0) gain_ = static_cast<float>(kTargetRms / std::sqrt(level_power_));
      window_power_ = 0.0;
      window_count_ = 0;
    }
  }
}

}  // namespace deepnav
