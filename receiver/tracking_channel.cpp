#include "receiver/tracking_channel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "receiver/correlator.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kPeriod = gps::kCodeLength_chips;

/// An untracked PRN's code for the noise correlator (the next PRN, wrapping).
int noise_prn(int prn) { return prn % gps::kMaxPrn + 1; }

}  // namespace

TrackingChannel::TrackingChannel(const TrackingConfig& config, const ChannelStart& start)
    : cfg_(config),
      start_(start),
      code_(&ca_code_chips(start.prn)),
      noise_code_(&ca_code_chips(noise_prn(start.prn))),
      next_sample_(start.sample_index),
      code_phase_chips_(start.code_phase_chips) {
  if (!(cfg_.sample_rate_hz > 0.0)) throw std::invalid_argument("tracking: sample rate must be positive");
  if (20 % cfg_.coherent_ms_after_bit_sync != 0)
    throw std::invalid_argument("tracking: coherent_ms_after_bit_sync must divide 20");
  nco_.carrier_doppler_hz = start.doppler_hz;
  nco_.code_rate_cps = gps::kCodeRate_cps * (1.0 + start.doppler_hz / gps::kL1_Hz);
}

void TrackingChannel::apply(const NcoCommand& command) { nco_ = command; }

double TrackingChannel::seconds_tracked() const { return tracked_s_; }

double TrackingChannel::code_chips_at(std::int64_t sample_index) const {
  const double dt = static_cast<double>(sample_index - next_sample_) / cfg_.sample_rate_hz;
  return static_cast<double>(code_period_) * kPeriod + code_phase_chips_ + dt * nco_.code_rate_cps;
}

void TrackingChannel::process(const SampleBlock& block, std::vector<CorrelatorEpoch>& out) {
  if (state_ == ChannelState::lost) return;
  const std::int64_t block_end = block.first_sample_index + static_cast<std::int64_t>(block.samples.size());
  if (next_sample_ >= block_end) return;
  std::int64_t idx = std::max(next_sample_, block.first_sample_index);
  if (idx > next_sample_) {
    // Gap or late start: carry the NCOs across and drop the partial integration.
    const double dt = static_cast<double>(idx - next_sample_) / cfg_.sample_rate_hz;
    const double chips = code_phase_chips_ + dt * nco_.code_rate_cps;
    code_period_ += static_cast<std::int64_t>(std::floor(chips / kPeriod));
    code_phase_chips_ = std::fmod(chips, kPeriod);
    carrier_phase_cycles_ += dt * nco_.carrier_doppler_hz;
    next_sample_ = idx;
    acc_first_ = -1;
    acc_samples_ = 0;
    acc_ms_ = 0;
    acc_e_ = acc_p_ = acc_l_ = acc_n_ = 0.0;
  }
  const double fs = cfg_.sample_rate_hz;
  while (idx < block_end) {
    const double code_step = nco_.code_rate_cps / fs;
    const int to_period_end = std::max(1, static_cast<int>(std::ceil((kPeriod - code_phase_chips_) / code_step - 1e-9)));
    const int n = static_cast<int>(std::min<std::int64_t>(to_period_end, block_end - idx));
    CorrelatorSpan span;
    span.carrier_phase_cycles = cfg_.if_hz * static_cast<double>(idx) / fs + carrier_phase_cycles_;
    span.carrier_step_cycles = (cfg_.if_hz + nco_.carrier_doppler_hz) / fs;
    span.code_phase_chips = code_phase_chips_;
    span.code_step_chips = code_step;
    span.spacing_chips = cfg_.spacing_chips;
    const CorrelatorSums s = correlate(block.samples.data() + (idx - block.first_sample_index), n, span, *code_, *noise_code_);
    if (acc_first_ < 0) acc_first_ = idx;
    acc_e_ += s.early;
    acc_p_ += s.prompt;
    acc_l_ += s.late;
    acc_n_ += s.noise;
    acc_samples_ += n;
    code_phase_chips_ += n * code_step;
    carrier_phase_cycles_ += n * nco_.carrier_doppler_hz / fs;
    idx += n;
    next_sample_ = idx;
    if (n == to_period_end) finish_code_period(out);
  }
}

void TrackingChannel::finish_code_period(std::vector<CorrelatorEpoch>& out) {
  code_phase_chips_ -= kPeriod;
  ++code_period_;
  ++acc_ms_;
  // Extended integrations end on data-bit edges.
  if (bit_edge_ && ((code_period_ - *bit_edge_) % coherent_ms_ + coherent_ms_) % coherent_ms_ != 0) return;
  CorrelatorEpoch e;
  e.prn = start_.prn;
  e.first_sample = acc_first_;
  e.samples = acc_samples_;
  e.integration_s = acc_samples_ / cfg_.sample_rate_hz;
  e.code_period = code_period_;
  e.early = acc_e_;
  e.prompt = acc_p_;
  e.late = acc_l_;
  e.noise = acc_n_;
  e.carrier_phase_cycles = carrier_phase_cycles_;
  e.carrier_doppler_hz = nco_.carrier_doppler_hz;
  e.code_rate_cps = nco_.code_rate_cps;
  out.push_back(e);
  phase_history_.emplace_back(next_sample_, carrier_phase_cycles_);
  while (phase_history_.size() > 64) phase_history_.pop_front();
  acc_first_ = -1;
  acc_samples_ = 0;
  acc_ms_ = 0;
  acc_e_ = acc_p_ = acc_l_ = acc_n_ = 0.0;
}

std::optional<double> TrackingChannel::mean_doppler_hz(double window_s) const {
  if (phase_history_.size() < 2) return std::nullopt;
  const auto& last = phase_history_.back();
  const auto window = static_cast<std::int64_t>(window_s * cfg_.sample_rate_hz);
  for (auto it = phase_history_.rbegin(); it != phase_history_.rend(); ++it) {
    if (last.first - it->first >= window) {
      return (last.second - it->second) * cfg_.sample_rate_hz / static_cast<double>(last.first - it->first);
    }
  }
  return std::nullopt;
}

void TrackingChannel::bit_sync_step(const CorrelatorEpoch& e) {
  // Sign changes of the 1 ms prompt (carrier locked: data in I) vote for the code period
  // at which a bit starts, modulo 20.
  if (last_prompt_ms_ && (last_prompt_ms_->real() * e.prompt.real() < 0.0)) {
    ++edge_votes_[static_cast<std::size_t>(((e.code_period - 1) % 20 + 20) % 20)];
    ++transitions_;
  }
  last_prompt_ms_ = e.prompt;
  if (transitions_ < 12) return;
  const auto best = std::max_element(edge_votes_.begin(), edge_votes_.end());
  if (*best >= 0.8 * transitions_) {
    bit_edge_ = static_cast<std::int64_t>(std::distance(edge_votes_.begin(), best));
    coherent_ms_ = cfg_.coherent_ms_after_bit_sync;
    state_ = ChannelState::tracking;
  } else if (transitions_ > 60) {
    edge_votes_.fill(0);  // no clear edge: start over
    transitions_ = 0;
  }
}

void TrackingChannel::monitor(const CorrelatorEpoch& e) {
  tracked_s_ += e.integration_s;
  lock_.add(e.prompt, e.noise, e.integration_s);
  if (state_ == ChannelState::pull_in && tracked_s_ > 0.3 && phase_locked()) state_ = ChannelState::bit_sync;
  if (state_ == ChannelState::bit_sync && e.integration_s < 1.5e-3) bit_sync_step(e);
  if (lock_.ready()) {
    // Weak or not phase-coherent for lost_after_s: the 1 ms C/N0 estimate alone has a noise
    // floor of about 25 dB-Hz over the window, the |I|/|Q| ratio separates noise from signal.
    if (lock_.cn0_dbhz() < cfg_.lost_cn0_dbhz || lock_.phase_lock_indicator() < 1.2) {
      if (low_cn0_since_s_ < 0.0) low_cn0_since_s_ = tracked_s_;
      if (tracked_s_ - low_cn0_since_s_ > cfg_.lost_after_s) state_ = ChannelState::lost;
    } else {
      low_cn0_since_s_ = -1.0;
    }
  }
}

}  // namespace deepnav
