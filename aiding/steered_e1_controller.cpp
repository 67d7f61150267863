#include "aiding/steered_e1_controller.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "aiding/measurement_models.hpp"
#include "receiver/tracking/e1_tracking_loops.hpp"

namespace deepnav::aiding {
namespace {

constexpr int kPeriodMs = 4;                         // one E1 code period
constexpr double kRateWindow_s = 0.1;                // phase-locked rate: adjoining windows, as for GPS
constexpr double kMaxWindowPhaseError_cycles = 0.1;  // a window's ends: phase error within +-36 deg
constexpr double kPhaseLock = 1.5;                   // mean I / mean |Q| of the wiped pilot: phase locked
constexpr double kReferenceIntegration_s = 0.01;     // the length min_cn0_dbhz is stated for
constexpr double kDetectionSigmas = 3.0;             // signal: 3 sigmas above noise alone
constexpr double kLockHold_s = 1.0;                  // locked: a measurement within this (or the longest integration)
constexpr std::size_t kRecent = 10;                  // integrations that show a sudden change at once

IntegrationPower power_of(const E1CorrelatorEpoch& e, double fs) {
  IntegrationPower p = coherent_power(e.prompt, e.noise, static_cast<double>(e.first_sample + e.samples) / fs,
                                      e.integration_s, e.noise_samples / fs);
  // The secondary-wiped pilot has no sign left: its prompt reads the phase error directly.
  p.wiped_prompt = e.prompt;
  p.data_wiped = true;
  return p;
}

}  // namespace

bool can_steer_e1(E1ChannelState state, bool time_mark, bool has_ephemeris, bool clock_set, bool offset_known) {
  return state == E1ChannelState::tracking && time_mark && has_ephemeris && clock_set && offset_known;
}

SteeredE1Controller::SteeredE1Controller(const UltraTightConfig& config, double sample_rate_hz,
                                         const Engagement& engagement, const bool& offset_known)
    : cfg_(config),
      fs_(sample_rate_hz),
      engagement_(engagement),
      offset_known_(offset_known),
      rate_window_(sample_rate_hz, kRateWindow_s) {}

int SteeredE1Controller::own_coherent_periods(const E1ChannelView& view) {
  return view.channel.config().coherent_ms_after_sync / kPeriodMs;
}

void SteeredE1Controller::forget_signal() {
  long_mode_ = false;
  rate_window_.reset();  // a window must lie inside one steered stretch
  recent_.clear();
}

E1ChannelDecision SteeredE1Controller::let_go(const E1ChannelView& view) {
  E1ChannelDecision out;
  if (steered_) {
    steered_ = false;
    out.loss_detection = true;
    out.coherent_periods = own_coherent_periods(view);
  }
  forget_signal();
  return out;
}

E1ChannelDecision SteeredE1Controller::on_epoch(const E1CorrelatorEpoch& e, const E1ChannelView& view) {
  const std::int64_t end = e.first_sample + e.samples;
  // Ultra-tight only. Faded E1 channels held through outages in the other modes, as GPS
  // ones are, left a suburban loose-coupling run of the Monte Carlo 26 m off (3.4 m with
  // the E1 channels on their own loops): not measured, such a channel's replica is the
  // filter's own prediction.
  if (engagement_ != Engagement::all) return let_go(view);
  const std::optional<double> tt = e1_transmit_time_sow(view.decoder, e);
  if (!can_steer_e1(e.state, tt.has_value(), view.ephemeris != nullptr, view.receiver_clock_set, offset_known_))
    return let_go(view);
  E1ChannelDecision out;
  out.owns_epoch = true;
  if (!steered_) {
    steered_ = true;
    out.loss_detection = false;
    out.coherent_periods = cfg_.e1_coherent_ms / kPeriodMs;
    cn0_.reset();
    spdlog::debug("{}: steered by the navigation filter", e.satellite.to_string());
  }
  cn0_.add(power_of(e, fs_));
  if (const std::optional<int> periods = choose_length(e)) out.coherent_periods = periods;
  const double cn0 = cn0_.ready() ? e1_signal_cn0_dbhz(cn0_.cn0_dbhz()) : e.cn0_dbhz;
  const double phase_error_cycles = pilot_phase_error_cycles(e.prompt);
  if (cfg_.carrier_phase_tracking) {
    const double gain = long_mode_ ? cfg_.long_phase_gain : cfg_.carrier_phase_gain;
    phase_correction_cycles_ = gain * phase_error_cycles;
  }
  DiscriminatorSample d = sample_of(e, *tt, cn0);
  recent_.push_back({e.prompt, d.code_error_chips});
  if (recent_.size() > kRecent) recent_.pop_front();
  rate_of(d, e, phase_error_cycles);
  const double reference_chips = code_sigma_chips(cfg_.min_cn0_dbhz, kReferenceIntegration_s, e.spacing_chips);
  const std::optional<double> recent_rms = recent_code_rms_chips();
  d.code_sigma_floor_chips = recent_rms.value_or(0.0);
  // A measurement only once the recent integrations floor its sigma.
  d.measurement = cn0_.ready() && cn0_.signal_detected(kDetectionSigmas) && recent_rms.has_value() &&
                  e1_code_sigma_chips(cn0, e.integration_s, e.spacing_chips) <= reference_chips;
  if (d.measurement) last_measurement_end_ = end;
  d.ephemeris = *view.ephemeris;
  outbox_.push_back(std::move(d));
  out.lock = lock_report(end, cn0);
  return out;
}

std::optional<int> SteeredE1Controller::choose_length(const E1CorrelatorEpoch& e) {
  if (!cn0_.ready()) return std::nullopt;
  const double cn0 = e1_signal_cn0_dbhz(cn0_.cn0_dbhz());
  const LongIntegrationConfig& lc = cfg_.long_integration;
  if (!long_mode_ && cn0 < lc.enter_below_dbhz) {
    long_mode_ = true;
    spdlog::debug("{}: C/N0 {:.1f} dB-Hz: {} ms pilot integrations", e.satellite.to_string(), cn0,
                  cfg_.e1_weak_coherent_ms);
    return cfg_.e1_weak_coherent_ms / kPeriodMs;
  }
  if (long_mode_ && cn0 > lc.leave_above_dbhz) {
    long_mode_ = false;
    spdlog::debug("{}: C/N0 {:.1f} dB-Hz: back to {} ms pilot integrations", e.satellite.to_string(), cn0,
                  cfg_.e1_coherent_ms);
    return cfg_.e1_coherent_ms / kPeriodMs;
  }
  return std::nullopt;
}

DiscriminatorSample SteeredE1Controller::sample_of(const E1CorrelatorEpoch& e, double transmit_sow,
                                                   double cn0_dbhz) const {
  // Referred to the integration's end, where the epoch gives the replica's NCO state (the
  // filter's code corrections inside it make extrapolating from the channel's present state
  // wrong); the code error is the integration's mean, which small corrections hardly move.
  DiscriminatorSample d;
  d.prn = e.satellite.prn;
  d.mid_sample = e.first_sample + e.samples;
  d.replica_transmit_sow = transmit_sow;
  d.code_error_chips = boc11_dll_code_error_chips(e.early, e.late, e.spacing_chips);
  d.spacing_chips = e.spacing_chips;
  d.cn0_dbhz = cn0_dbhz;
  d.integration_s = e.integration_s;
  d.data_wiped = true;
  return d;
}

void SteeredE1Controller::rate_of(DiscriminatorSample& d, const E1CorrelatorEpoch& e, double phase_error_cycles) {
  const bool locked = cn0_.wiped_phase_lock_indicator() > kPhaseLock && recently_phase_locked();
  if (!cfg_.carrier_phase_tracking || !locked || std::abs(phase_error_cycles) >= kMaxWindowPhaseError_cycles) {
    rate_window_.reset();
    return;
  }
  // Phase-locked: the carrier phase at the end is the NCO's plus the error the prompt shows.
  if (const std::optional<WindowRate> r =
          rate_window_.add(e.first_sample + e.samples, e.carrier_phase_cycles + phase_error_cycles, e.samples)) {
    d.doppler_hz = r->doppler_hz;
    d.doppler_sample = r->mid_sample;
    d.rate_window_s = r->window_s;
  }
}

std::optional<double> SteeredE1Controller::recent_code_rms_chips() const {
  if (recent_.size() < kRecent) return std::nullopt;
  double sum2 = 0.0;
  for (const Recent& r : recent_) sum2 += r.code_error_chips * r.code_error_chips;
  return std::sqrt(sum2 / static_cast<double>(recent_.size()));
}

bool SteeredE1Controller::recently_phase_locked() const {
  if (recent_.size() < kRecent) return false;
  // The wiped pilot's prompt is positive real when locked; with noise alone the ratio
  // scatters about 0 (sigma about 0.4 for ten integrations).
  double i = 0.0, q = 0.0;
  for (const Recent& r : recent_) {
    i += r.prompt.real();
    q += std::abs(r.prompt.imag());
  }
  return q > 0.0 && i / q > kPhaseLock;
}

SignalLockReport SteeredE1Controller::lock_report(std::int64_t end_sample, double cn0_dbhz) const {
  SignalLockReport r;
  r.cn0_dbhz = cn0_dbhz;
  const double hold_s = std::max(kLockHold_s, 1e-3 * cfg_.e1_weak_coherent_ms + 0.02);
  r.locked = last_measurement_end_ && static_cast<double>(end_sample - *last_measurement_end_) <= hold_s * fs_;
  return r;
}

E1ChannelDecision SteeredE1Controller::between_blocks(const E1ChannelView& view) {
  E1ChannelDecision out;
  out.command = inbox_command_;
  if (inbox_release_) {
    out.loss_detection = true;
    out.coherent_periods = own_coherent_periods(view);
  }
  inbox_command_.reset();
  inbox_release_ = false;
  return out;
}

std::vector<DiscriminatorSample> SteeredE1Controller::take_samples() {
  std::vector<DiscriminatorSample> samples;
  samples.swap(outbox_);
  return samples;
}

void SteeredE1Controller::publish(const NcoCommand& command) {
  NcoCommand cmd = command;
  if (cfg_.carrier_phase_tracking && phase_correction_cycles_ != 0.0) {
    cmd.carrier_phase_correction_cycles = phase_correction_cycles_;
    phase_correction_cycles_ = 0.0;
  }
  inbox_command_ = cmd;
}

void SteeredE1Controller::publish_release() {
  steered_ = false;
  inbox_release_ = true;
  forget_signal();
}

void SteeredE1Controller::release() {
  if (steered_) inbox_release_ = true;
  steered_ = false;
  outbox_.clear();
  forget_signal();
}

}  // namespace deepnav::aiding
