#include "receiver/tracking/e1_tracking_channel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "signals/galileo/e1_modulation.hpp"

namespace deepnav {
namespace {

constexpr double kPeriod = galileo::kE1CodeLength_chips;
constexpr int kPeriodMs = 4;
constexpr int kMaxCoherentPeriods = 25;  // 100 ms: one CS25 period
constexpr double kMinSampleRate_hz = 2.1e6;

/// An untracked PRN's pilot code for the noise reference: the next PRN.
int noise_reference_prn_e1(int prn) { return prn % galileo::kMaxPrn + 1; }

E1CorrelatorSums scaled(const E1CorrelatorSums& s, double pilot_factor) {
  E1CorrelatorSums out = s;
  out.very_early *= pilot_factor;
  out.early *= pilot_factor;
  out.prompt *= pilot_factor;
  out.late *= pilot_factor;
  out.very_late *= pilot_factor;
  return out;
}

void add_to(E1CorrelatorSums& acc, const E1CorrelatorSums& s) {
  acc.very_early += s.very_early;
  acc.early += s.early;
  acc.prompt += s.prompt;
  acc.late += s.late;
  acc.very_late += s.very_late;
  acc.data_prompt += s.data_prompt;
  acc.noise += s.noise;
}

}  // namespace

double e1_pilot_power_fraction() { return 0.5 * galileo::kCbocAlpha * galileo::kCbocAlpha; }

E1TrackingChannel::E1TrackingChannel(const E1TrackingConfig& config, const E1ChannelStart& start)
    : cfg_(config),
      start_(start),
      next_sample_(start.sample_index),
      code_phase_chips_(start.code_phase_chips),
      sync_(config.secondary_window_periods),
      guard_(config.side_peak_threshold, config.side_peak_max_jumps) {
  if (start.satellite.system != GnssSystem::galileo)
    throw std::invalid_argument("E1 tracking: satellite " + start.satellite.to_string() +
                                " is not a Galileo satellite");
  if (!(cfg_.sample_rate_hz >= kMinSampleRate_hz))
    throw std::invalid_argument("E1 tracking: sample_rate_hz must be at least 2.1e6 (a sample per BOC(1,1) half chip)");
  if (!(cfg_.pull_in_s >= 0.0) || !(cfg_.secondary_timeout_s > 0.0) || !(cfg_.lost_after_s > 0.0))
    throw std::invalid_argument("E1 tracking: pull_in_s must be >= 0, secondary_timeout_s and lost_after_s > 0");
  if (cfg_.coherent_ms_after_sync < kPeriodMs || cfg_.coherent_ms_after_sync > 100 ||
      cfg_.coherent_ms_after_sync % kPeriodMs != 0)
    throw std::invalid_argument("E1 tracking: coherent_ms_after_sync must be a multiple of 4 in 4..100, got " +
                                std::to_string(cfg_.coherent_ms_after_sync));
  if (!(cfg_.spacing_chips > 0.0 && cfg_.spacing_chips < 2.0 / 3.0))
    throw std::invalid_argument("E1 tracking: spacing_chips must be in (0, 2/3) for the BOC(1,1) main peak");
  if (!(cfg_.very_spacing_chips >= 0.0 && cfg_.very_spacing_chips <= 2.0))
    throw std::invalid_argument("E1 tracking: very_spacing_chips must be in [0, 2]");
  if (!(start.code_phase_chips >= 0.0 && start.code_phase_chips < kPeriod))
    throw std::invalid_argument("E1 tracking: start code phase must be in [0, 4092) chips");
  codes_.pilot = &galileo::e1c_code_chips(start.satellite.prn);
  codes_.data = &galileo::e1b_code_chips(start.satellite.prn);
  codes_.noise = &galileo::e1c_code_chips(noise_reference_prn_e1(start.satellite.prn));
  // The lock detector sees the pilot alone; its C/N0 thresholds are given for the whole signal.
  const double pilot_db = 10.0 * std::log10(e1_pilot_power_fraction());
  LockThresholds th = cfg_.lock;
  th.code_on_dbhz += pilot_db;
  th.code_off_dbhz += pilot_db;
  lock_ = LockDetector(th);
  nco_.carrier_doppler_hz = start.doppler_hz;
  nco_.code_rate_cps = galileo::kE1CodeRate_cps * (1.0 + start.doppler_hz / galileo::kE1_Hz);
}

double E1TrackingChannel::cn0_dbhz() const {
  const double pilot = lock_.cn0_dbhz();
  return pilot > 0.0 ? pilot - 10.0 * std::log10(e1_pilot_power_fraction()) : 0.0;
}

void E1TrackingChannel::apply(const NcoCommand& command) {
  nco_.code_rate_cps = command.code_rate_cps;
  nco_.carrier_doppler_hz = command.carrier_doppler_hz;
  if (command.carrier_phase_correction_cycles) carrier_phase_cycles_ += *command.carrier_phase_correction_cycles;
  if (command.code_phase_correction_chips) jump_replica(*command.code_phase_correction_chips);
}

void E1TrackingChannel::set_loss_detection(bool on) {
  loss_detection_ = on;
  low_since_s_ = -1.0;  // a fade is timed afresh once the rule is back
}

void E1TrackingChannel::set_coherent_periods(int periods) {
  if (periods < 1 || periods > kMaxCoherentPeriods)
    throw std::invalid_argument("E1 tracking: coherent periods must be 1 to 25 (4 to 100 ms), got " +
                                std::to_string(periods));
  if (state_ == E1ChannelState::tracking) coherent_periods_ = periods;
}

void E1TrackingChannel::jump_replica(double chips) {
  // The period count carries whole periods, so code_chips_at() stays continuous across the jump.
  const double moved = code_phase_chips_ + chips;
  const double periods = std::floor(moved / kPeriod);
  code_period_ += static_cast<std::int64_t>(periods);
  code_phase_chips_ = moved - periods * kPeriod;
}

double E1TrackingChannel::code_chips_at(std::int64_t sample_index) const {
  const double dt = static_cast<double>(sample_index - next_sample_) / cfg_.sample_rate_hz;
  return static_cast<double>(code_period_) * kPeriod + code_phase_chips_ + dt * nco_.code_rate_cps;
}

void E1TrackingChannel::reset_integration() {
  acc_ = {};
  acc_first_ = -1;
  acc_samples_ = 0;
  acc_noise_samples_ = 0;
  acc_periods_ = 0;
  symbols_.clear();
}

void E1TrackingChannel::process(const SampleBlock& block,
                                const std::function<void(const E1CorrelatorEpoch&)>& on_epoch) {
  if (state_ == E1ChannelState::lost) return;
  const std::int64_t block_end = block.first_sample_index + static_cast<std::int64_t>(block.samples.size());
  if (next_sample_ >= block_end) return;
  std::int64_t idx = std::max(next_sample_, block.first_sample_index);
  const double fs = cfg_.sample_rate_hz;
  if (idx > next_sample_) {
    // Gap or late start: carry the NCOs across and drop the partial period and integration.
    const double dt = static_cast<double>(idx - next_sample_) / fs;
    jump_replica(dt * nco_.code_rate_cps);
    carrier_phase_cycles_ += dt * nco_.carrier_doppler_hz;
    next_sample_ = idx;
    period_ = {};
    period_first_ = -1;
    period_samples_ = 0;
    reset_integration();
    sync_.reset();
  }
  while (idx < block_end) {
    const double code_step = nco_.code_rate_cps / fs;
    const int to_period_end =
        std::max(1, static_cast<int>(std::ceil((kPeriod - code_phase_chips_) / code_step - 1e-9)));
    const int n = static_cast<int>(std::min<std::int64_t>(to_period_end, block_end - idx));
    E1CorrelatorSpan span;
    span.carrier_phase_cycles = cfg_.if_hz * static_cast<double>(idx) / fs + carrier_phase_cycles_;
    span.carrier_step_cycles = (cfg_.if_hz + nco_.carrier_doppler_hz) / fs;
    span.code_phase_chips = code_phase_chips_;
    span.code_step_chips = code_step;
    span.spacing_chips = cfg_.spacing_chips;
    span.very_spacing_chips = cfg_.very_spacing_chips;
    // The noise reference on an integration's first period only: the C/N0 estimate averages
    // it over seconds, and the pass costs nearly as much as the pilot's five taps.
    span.noise_tap = acc_periods_ == 0;
    span.magnitude_bits = block.magnitude_bits;
    const auto offset = static_cast<std::size_t>(idx - block.first_sample_index);
    CorrelatorInput input{block.samples.data() + offset};
    if (block.planar.size() == 2 * block.samples.size()) {
      input.i = block.planar.data() + offset;
      input.q = block.planar.data() + block.samples.size() + offset;
    }
    add_to(period_, correlate_e1(input, n, span, codes_));
    if (period_first_ < 0) period_first_ = idx;
    period_samples_ += n;
    code_phase_chips_ += n * code_step;
    carrier_phase_cycles_ += n * nco_.carrier_doppler_hz / fs;
    idx += n;
    next_sample_ = idx;
    if (n == to_period_end) {
      if (auto e = finish_code_period()) {
        on_epoch(*e);
        if (state_ == E1ChannelState::lost) return;
      }
    }
  }
}

std::optional<E1CorrelatorEpoch> E1TrackingChannel::finish_code_period() {
  code_phase_chips_ -= kPeriod;
  const std::int64_t period = code_period_++;  // the period just completed, counted from 0
  const E1CorrelatorSums sums = period_;
  const std::int64_t first = period_first_;
  const int samples = period_samples_;
  period_ = {};
  period_first_ = -1;
  period_samples_ = 0;
  // Period 0 is partial when the channel started mid-period: no symbol, no sync prompt.
  const bool whole = period > 0 || start_.code_phase_chips == 0.0;
  if (whole) {
    const double polarity = secondary_ ? -1.0 : 1.0;
    symbols_.push_back(E1bSymbol{polarity * sums.data_prompt.real(), first, period, secondary_.has_value()});
  }
  double pilot_sign = 1.0;
  // The search runs on phase-locked prompts only: with a frequency error left the sign of the
  // wiped sum, which fixes the carrier phase from then on, would be a guess.
  if (state_ == E1ChannelState::secondary_sync && whole && lock_.pll_locked()) {
    if (const auto found = sync_.add(period, sums.prompt)) {
      secondary_ = found;
      if (found->prompt_sign < 0) {
        // The Costas loop sat half a cycle off the pilot's phase: turn the carrier so the
        // wiped prompt is positive from the next sample on (and read this one as if it were).
        carrier_phase_cycles_ += 0.5;
        pilot_sign = -1.0;
      }
      state_ = E1ChannelState::tracking;
    }
  }
  if (secondary_) pilot_sign *= secondary_chip(period, secondary_->offset);
  add_to(acc_, scaled(sums, pilot_sign));
  if (acc_first_ < 0) acc_first_ = first;
  acc_samples_ += samples;
  if (acc_periods_ == 0) acc_noise_samples_ += samples;
  if (++acc_periods_ < coherent_periods_ && state_ == E1ChannelState::tracking) return std::nullopt;

  E1CorrelatorEpoch e;
  e.satellite = start_.satellite;
  e.channel = start_.channel;
  e.first_sample = acc_first_;
  e.samples = acc_samples_;
  e.integration_s = acc_samples_ / cfg_.sample_rate_hz;
  e.code_period = code_period_;
  e.very_early = acc_.very_early;
  e.early = acc_.early;
  e.prompt = acc_.prompt;
  e.late = acc_.late;
  e.very_late = acc_.very_late;
  e.spacing_chips = cfg_.spacing_chips;
  e.very_spacing_chips = cfg_.very_spacing_chips;
  e.data_prompt = sums.data_prompt;
  e.noise = acc_.noise;
  e.noise_samples = acc_noise_samples_;
  e.code_phase_chips = code_phase_chips_;
  e.carrier_phase_cycles = carrier_phase_cycles_;
  e.carrier_doppler_hz = nco_.carrier_doppler_hz;
  e.code_rate_cps = nco_.code_rate_cps;
  e.secondary_synced = secondary_.has_value();
  e.symbols = std::move(symbols_);
  reset_integration();
  monitor(e);
  return e;
}

void E1TrackingChannel::monitor(E1CorrelatorEpoch& e) {
  tracked_s_ += e.integration_s;
  lock_.add(e.prompt, e.noise, e.integration_s, e.noise_samples / cfg_.sample_rate_hz);
  if (state_ == E1ChannelState::pull_in && tracked_s_ >= cfg_.pull_in_s) state_ = E1ChannelState::secondary_sync;
  if (state_ == E1ChannelState::secondary_sync && tracked_s_ >= cfg_.pull_in_s + cfg_.secondary_timeout_s)
    state_ = E1ChannelState::lost;
  // Longer integrations only with the phase locked: a frequency error the 4 ms loop still has
  // would alias in them (20 ms integrations see only +-25 Hz). The lock window starts afresh
  // with the new length, and so does the weak-signal timer.
  if (state_ == E1ChannelState::tracking && coherent_periods_ == 1 && lock_.pll_locked()) {
    coherent_periods_ = cfg_.coherent_ms_after_sync / kPeriodMs;
    low_since_s_ = -1.0;
  }
  if (cfg_.very_spacing_chips > 0.0) {
    const double jump = guard_.add(e.very_early, e.prompt, e.very_late);
    if (jump != 0.0) {
      // Between a negative side peak and the positive main peak the prompt changes sign.
      jump_replica(jump);
      carrier_phase_cycles_ += 0.5;
    }
    if (guard_.exhausted()) state_ = E1ChannelState::lost;
  }
  if (lock_.ready() && loss_detection_) {
    // Weak or not phase-coherent for lost_after_s (either test alone passes noise now and then).
    if (cn0_dbhz() < cfg_.lost_cn0_dbhz || lock_.phase_lock_indicator() < 1.2) {
      if (low_since_s_ < 0.0) low_since_s_ = tracked_s_;
      if (tracked_s_ - low_since_s_ > cfg_.lost_after_s) state_ = E1ChannelState::lost;
    } else {
      low_since_s_ = -1.0;
    }
  }
  e.cn0_dbhz = cn0_dbhz();
  e.pll_lock = lock_.pll_locked();
  e.code_lock = lock_.code_locked();
  e.state = state_;
}

}  // namespace deepnav
