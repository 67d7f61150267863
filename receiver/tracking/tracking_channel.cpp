#include "receiver/tracking/tracking_channel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "receiver/tracking/correlator.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kPeriod = gps::kCodeLength_chips;
/// Prompts kept before bit synchronisation: a frame and a subframe (36 s), more than any
/// cold start needs before its first complete subframe.
constexpr std::size_t kHistoryPeriods = 36000;

}  // namespace

TrackingChannel::TrackingChannel(const TrackingConfig& config, const ChannelStart& start)
    : cfg_(config),
      start_(start),
      code_(&ca_code_chips(start.prn)),
      noise_code_(&ca_code_chips(noise_reference_prn(start.prn))),
      next_sample_(start.sample_index),
      code_phase_chips_(start.code_phase_chips),
      lock_(config.lock),
      history_(kHistoryPeriods) {
  if (!(cfg_.sample_rate_hz > 0.0)) throw std::invalid_argument("tracking: sample rate must be positive");
  if (cfg_.coherent_ms_after_bit_sync < 1 || 20 % cfg_.coherent_ms_after_bit_sync != 0)
    throw std::invalid_argument("tracking: coherent_ms_after_bit_sync must divide 20 (1, 2, 4, 5, 10 or 20), got " +
                                std::to_string(cfg_.coherent_ms_after_bit_sync));
  if (start.prn < 1 || start.prn > gps::kMaxPrn)
    throw std::invalid_argument("tracking: PRN must be in 1..32, got " + std::to_string(start.prn));
  if (!(cfg_.spacing_chips > 0.0 && cfg_.spacing_chips < 2.0) || !(cfg_.very_spacing_chips >= 0.0))
    throw std::invalid_argument(
        "tracking: early-late spacing must be in (0, 2) chips and very-early/late spacing >= 0");
  nco_.carrier_doppler_hz = start.doppler_hz;
  nco_.code_rate_cps = gps::kCodeRate_cps * (1.0 + start.doppler_hz / gps::kL1_Hz);
  if (start.bit_edge_period) {
    bit_edge_ = code_periods_into_bit(*start.bit_edge_period, 0);
    coherent_ms_ = cfg_.coherent_ms_after_bit_sync;
    state_ = ChannelState::tracking;
  }
}

void TrackingChannel::apply(const NcoCommand& command) {
  nco_.code_rate_cps = command.code_rate_cps;
  nco_.carrier_doppler_hz = command.carrier_doppler_hz;
  if (command.carrier_phase_correction_cycles) carrier_phase_cycles_ += *command.carrier_phase_correction_cycles;
  if (command.code_phase_correction_chips) {
    // Keep the phase in [0, 1023) with the period count carrying the whole periods, so
    // code_chips_at() stays continuous across the jump.
    const double chips = code_phase_chips_ + *command.code_phase_correction_chips;
    const double periods = std::floor(chips / kPeriod);
    code_period_ += static_cast<std::int64_t>(periods);
    code_phase_chips_ = chips - periods * kPeriod;
  }
}

void TrackingChannel::reset_integration() {
  acc_first_ = -1;
  acc_samples_ = 0;
  acc_ms_ = 0;
  acc_e_ = acc_p_ = acc_l_ = acc_ve_ = acc_vl_ = acc_n_ = 0.0;
  acc_n_samples_ = 0;
}

std::vector<PromptBit> TrackingChannel::take_bits() {
  std::vector<PromptBit> b;
  b.swap(bits_);
  return b;
}

double TrackingChannel::seconds_tracked() const { return tracked_s_; }

double TrackingChannel::code_chips_at(std::int64_t sample_index) const {
  const double dt = static_cast<double>(sample_index - next_sample_) / cfg_.sample_rate_hz;
  return static_cast<double>(code_period_) * kPeriod + code_phase_chips_ + dt * nco_.code_rate_cps;
}

void TrackingChannel::process(const SampleBlock& block, std::vector<CorrelatorEpoch>& out) {
  process(block, [&out](const CorrelatorEpoch& e) { out.push_back(e); });
}

void TrackingChannel::process(const SampleBlock& block, const std::function<void(const CorrelatorEpoch&)>& on_epoch) {
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
    reset_integration();
    bit_ms_ = 0;  // the bit in progress lost samples too
  }
  const double fs = cfg_.sample_rate_hz;
  while (idx < block_end) {
    const double code_step = nco_.code_rate_cps / fs;
    const int to_period_end =
        std::max(1, static_cast<int>(std::ceil((kPeriod - code_phase_chips_) / code_step - 1e-9)));
    const int n = static_cast<int>(std::min<std::int64_t>(to_period_end, block_end - idx));
    CorrelatorSpan span;
    span.carrier_phase_cycles = cfg_.if_hz * static_cast<double>(idx) / fs + carrier_phase_cycles_;
    span.carrier_step_cycles = (cfg_.if_hz + nco_.carrier_doppler_hz) / fs;
    span.code_phase_chips = code_phase_chips_;
    span.code_step_chips = code_step;
    span.spacing_chips = cfg_.spacing_chips;
    span.very_spacing_chips = cfg_.very_spacing_chips;
    span.magnitude_bits = block.magnitude_bits;
    span.noise_tap = acc_ms_ == 0 || cfg_.noise_on_every_period;
    const auto offset = static_cast<std::size_t>(idx - block.first_sample_index);
    CorrelatorInput input{block.samples.data() + offset};
    if (block.planar.size() == 2 * block.samples.size()) {
      input.i = block.planar.data() + offset;
      input.q = block.planar.data() + block.samples.size() + offset;
    }
    const CorrelatorSums s = correlate(input, n, span, *code_, *noise_code_);
    if (acc_first_ < 0) acc_first_ = idx;
    acc_e_ += s.early;
    acc_p_ += s.prompt;
    acc_l_ += s.late;
    acc_ve_ += s.very_early;
    acc_vl_ += s.very_late;
    if (span.noise_tap) {
      acc_n_ += s.noise;
      acc_n_samples_ += n;
    }
    acc_samples_ += n;
    code_phase_chips_ += n * code_step;
    carrier_phase_cycles_ += n * nco_.carrier_doppler_hz / fs;
    idx += n;
    next_sample_ = idx;
    if (n == to_period_end) {
      if (const auto e = finish_code_period()) {
        on_epoch(*e);
        if (state_ == ChannelState::lost) return;
      }
    }
  }
}

std::optional<CorrelatorEpoch> TrackingChannel::finish_code_period() {
  code_phase_chips_ -= kPeriod;
  ++code_period_;
  ++acc_ms_;
  // Extended integrations end on data-bit edges.
  if (bit_edge_ && ((code_period_ - *bit_edge_) % coherent_ms_ + coherent_ms_) % coherent_ms_ != 0) return std::nullopt;
  CorrelatorEpoch e;
  e.prn = start_.prn;
  e.channel = start_.channel;
  e.first_sample = acc_first_;
  e.samples = acc_samples_;
  e.integration_s = acc_samples_ / cfg_.sample_rate_hz;
  e.code_period = code_period_;
  e.early = acc_e_;
  e.prompt = acc_p_;
  e.late = acc_l_;
  e.spacing_chips = cfg_.spacing_chips;
  e.very_early = acc_ve_;
  e.very_late = acc_vl_;
  e.noise = acc_n_;
  e.noise_samples = acc_n_samples_;
  e.code_phase_chips = code_phase_chips_;
  e.carrier_phase_cycles = carrier_phase_cycles_;
  e.carrier_doppler_hz = nco_.carrier_doppler_hz;
  e.code_rate_cps = nco_.code_rate_cps;
  phase_history_.emplace_back(next_sample_, carrier_phase_cycles_);
  while (phase_history_.size() > 64) phase_history_.pop_front();
  reset_integration();
  // Monitoring may switch the integration length; the next integration starts afterwards.
  monitor(e);
  e.cn0_dbhz = lock_.cn0_dbhz();
  e.pll_lock = lock_.pll_locked();
  e.code_lock = lock_.code_locked();
  e.bit_synced = bit_edge_.has_value();
  return e;
}

void TrackingChannel::collect_bit(const CorrelatorEpoch& e) {
  // Integrations never straddle a bit edge once synchronised; a bit is complete when the
  // 20 code periods from its edge have been summed (the first, partial one is skipped).
  const int ms = static_cast<int>(std::lround(e.integration_s * 1000.0));
  const std::int64_t start = e.code_period - ms;
  const auto phase = [&](std::int64_t p) { return code_periods_into_bit(p, *bit_edge_); };
  if (phase(start) == 0) {
    bit_sum_ = 0.0;
    bit_ms_ = 0;
    bit_first_sample_ = e.first_sample;
    bit_first_period_ = start;
    // A channel started mid-period (a guided start, bit edges known at once) has a partial
    // period 0: an integration through it rounds to whole milliseconds but is not a whole bit.
    bit_whole_ = start > 0 || start_.code_phase_chips == 0.0;
  }
  bit_sum_ += e.prompt.real();
  bit_ms_ += ms;
  if (phase(e.code_period) != 0) return;
  if (bit_ms_ == 20 && bit_whole_) bits_.push_back(PromptBit{bit_sum_, bit_first_sample_, bit_first_period_});
  bit_ms_ = 0;
}

const std::pair<std::int64_t, double>* TrackingChannel::window_start(double window_s) const {
  if (phase_history_.size() < 2) return nullptr;
  const auto window = static_cast<std::int64_t>(window_s * cfg_.sample_rate_hz);
  for (auto it = phase_history_.rbegin(); it != phase_history_.rend(); ++it)
    if (phase_history_.back().first - it->first >= window) return &*it;
  return nullptr;
}

std::optional<double> TrackingChannel::mean_doppler_mid_sample(double window_s) const {
  const auto* start = window_start(window_s);
  if (start == nullptr) return std::nullopt;
  return 0.5 * static_cast<double>(phase_history_.back().first + start->first);
}

std::optional<double> TrackingChannel::mean_doppler_hz(double window_s) const {
  const auto* start = window_start(window_s);
  if (start == nullptr) return std::nullopt;
  const auto& last = phase_history_.back();
  return (last.second - start->second) * cfg_.sample_rate_hz / static_cast<double>(last.first - start->first);
}

void TrackingChannel::bit_sync_step(const CorrelatorEpoch& e) {
  // The epoch covers code period e.code_period - 1 (counted from 0).
  // 1 ms integrations: every one has its noise sum.
  if (const auto edge = bit_sync_.add(e.code_period - 1, e.prompt, e.noise)) {
    bit_edge_ = *edge;
    coherent_ms_ = cfg_.coherent_ms_after_bit_sync;
    state_ = ChannelState::tracking;
    release_history();
  }
}

void TrackingChannel::release_history() {
  PromptHistory::Bits kept = history_.bits(*bit_edge_);
  history_.clear();
  bits_.insert(bits_.end(), kept.whole.begin(), kept.whole.end());
  // The bit under way: its first periods were kept, collect_bit() adds the rest.
  bit_sum_ = kept.tail.soft;
  bit_ms_ = kept.tail.periods;
  bit_first_sample_ = kept.tail.first_sample;
  bit_first_period_ = kept.tail.code_period;
  bit_whole_ = true;
}

void TrackingChannel::monitor(const CorrelatorEpoch& e) {
  const bool synced_before = bit_edge_.has_value();
  tracked_s_ += e.integration_s;
  lock_.add(e.prompt, e.noise, e.integration_s, e.noise_samples / cfg_.sample_rate_hz);
  // Pull-in (FLL assistance) lasts a fixed time: long enough to bring an acquisition
  // frequency error of a few hundred hertz into the PLL's range, short enough that the FLL's
  // own noise (tens of hertz at 30 dB-Hz with 1 ms) does not keep the PLL from locking.
  if (state_ == ChannelState::pull_in && tracked_s_ >= cfg_.pull_in_s) state_ = ChannelState::bit_sync;
  // Every whole 1 ms period before synchronisation is kept (period 0 is partial when the
  // channel started mid-period); the synchroniser itself starts after pull-in.
  const bool whole_period = e.code_period > 1 || start_.code_phase_chips == 0.0;
  if (!synced_before && e.integration_s < 1.5e-3 && whole_period)
    history_.add(e.code_period - 1, e.prompt, e.first_sample);
  if (state_ == ChannelState::bit_sync && e.integration_s < 1.5e-3) bit_sync_step(e);
  if (synced_before) collect_bit(e);
  if (lock_.ready()) {
    // Weak or not phase-coherent for lost_after_s: either test alone can be passed by noise
    // now and then (a Costas loop turns noise into I), together they rarely are.
    if (lock_.cn0_dbhz() < cfg_.lost_cn0_dbhz || lock_.phase_lock_indicator() < 1.2) {
      if (low_cn0_since_s_ < 0.0) low_cn0_since_s_ = tracked_s_;
      if (loss_detection_ && tracked_s_ - low_cn0_since_s_ > cfg_.lost_after_s) state_ = ChannelState::lost;
    } else {
      low_cn0_since_s_ = -1.0;
    }
  }
}

}  // namespace deepnav
