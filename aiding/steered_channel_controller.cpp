#include "aiding/steered_channel_controller.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "aiding/measurement_models.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/tracking/tracking_loops.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kRateWindow_s = 0.1;                // phase-locked rate: adjoining windows of the mean frequency
constexpr double kMaxWindowPhaseError_cycles = 0.1;  // a window's ends: Costas error within +-36 deg
constexpr double kWipedPhaseLock = 1.5;              // mean I / mean |Q| of wiped integrations: phase locked
constexpr double kReferenceIntegration_s = 0.01;     // the length min_cn0_dbhz is stated for
constexpr double kDetectionSigmas = 3.0;             // a long integration's signal: 3 sigmas above noise alone
constexpr double kLockHold_s = 1.0;                  // locked: a measurement within this (the scalar loss time) ...

/// A discriminator sample of integration `e`, referred to `at_sample`, where the replica's
/// transmit time is `replica_transmit_sow`.
DiscriminatorSample sample_at(const CorrelatorEpoch& e, std::int64_t at_sample, double replica_transmit_sow) {
  DiscriminatorSample d;
  d.prn = e.prn;
  d.mid_sample = at_sample;
  d.replica_transmit_sow = replica_transmit_sow;
  d.spacing_chips = e.spacing_chips;
  d.integration_s = e.integration_s;
  return d;
}

}  // namespace

bool can_steer(bool bit_synced, ChannelState state, bool decoder_synchronised, bool has_ephemeris) {
  return bit_synced && state != ChannelState::lost && decoder_synchronised && has_ephemeris;
}

SteeredChannelController::SteeredChannelController(const UltraTightConfig& config, double sample_rate_hz,
                                                   const Engagement& engagement)
    : cfg_(config),
      fs_(sample_rate_hz),
      engagement_(engagement),
      rate_window_(sample_rate_hz, kRateWindow_s),
      long_(config.long_integration) {}

ChannelDecision SteeredChannelController::on_epoch(const CorrelatorEpoch& e, const ChannelView& view) {
  ChannelDecision out;
  const std::int64_t end = e.first_sample + e.samples;
  std::optional<double> doppler;
  if (end_sample_ == e.first_sample) {
    // Consecutive integrations: the phase advance between their prompts is the mean
    // residual frequency over the interval between their centres.
    // A phase correction applied between them turned the replica: add its share back.
    doppler = 0.5 * (doppler_hz_ + e.carrier_doppler_hz) + fll_frequency_error_hz(prompt_, e.prompt, e.integration_s) +
              applied_correction_cycles_ / e.integration_s;
  }
  applied_correction_cycles_ = 0.0;
  prompt_ = e.prompt;
  end_sample_ = end;
  doppler_hz_ = e.carrier_doppler_hz;
  const bool was_steered = steered_;
  bool engaged = engagement_ == Engagement::all;
  if (engagement_ == Engagement::faded_only) {
    // C/N0 reads 0 until the channel's estimator window is full: not a fade.
    const bool faded = e.cn0_dbhz > 0.0 && e.cn0_dbhz < cfg_.faded_below_dbhz;
    engaged = faded || (was_steered && e.cn0_dbhz < cfg_.recovered_above_dbhz);
  }
  const TrackingChannel& ch = view.channel;
  if (!engaged || !can_steer(e.bit_synced, ch.state(), view.decoder.synchronised(), view.ephemeris != nullptr) ||
      !view.receiver_clock_set) {
    if (was_steered) {
      steered_ = false;
      out.loss_detection = true;
    }
    rate_window_.reset();  // a window must lie inside one steered stretch
    leave_long_integration();
    return out;
  }
  out.owns_epoch = true;
  if (!was_steered) {
    steered_ = true;
    out.loss_detection = false;
    spdlog::debug("PRN {:2d}: steered by the navigation filter", e.prn);
  }
  wipeoff_.learn(view.decoder);
  if (cfg_.long_integration.assist_data_bits) wipeoff_.assist(*view.ephemeris);
  if (!long_mode_) {
    cn0_.add(power_of(e, fs_));
    choose_integration(e);
    if (!long_mode_) {
      short_sample(e, view, doppler);
      if (engagement_ == Engagement::all) out.lock = lock_report(end, e.cn0_dbhz);
      return out;
    }
  }
  std::vector<SteeredIntegration> done;
  const int polarity = view.decoder.polarity();
  const Ephemeris& eph = *view.ephemeris;
  const LongIntegrator::BitSigner signer = [&](std::int64_t bit_start, const std::complex<double>& bit_prompt) {
    const std::optional<std::int64_t> bit = DataWipeoff::bit_index(view.decoder, eph, bit_start);
    if (!bit) return 0;
    const int sign = wipeoff_.wipe_sign(*bit, polarity);  // before the bit teaches the monitor anything
    const NavBitMonitor::Check c =
        wipeoff_.observe(*bit, bit_prompt, long_.phase_reference(), polarity, cn0_.cn0_dbhz());
    if (c.alarm) spdlog::debug("PRN {:2d}: prediction of bit {} failed (segment {})", e.prn, *bit, c.segment);
    // Unpredicted bits: the Costas loop on each bit holds the phase (half-cycle ambiguous;
    // the four-quadrant loop of the next wiped integration settles that).
    if (sign == 0 && cfg_.carrier_phase_tracking)
      phase_correction_cycles_ = cfg_.carrier_phase_gain * costas_phase_error_cycles(bit_prompt);
    return sign;
  };
  long_.add(e, *ch.bit_edge_period(), signer, done);
  for (const SteeredIntegration& s : done) {
    cn0_.add(power_of(s, fs_));
    long_sample(s, view);
  }
  choose_integration(e);
  // Only ultra-tight measures with these integrations; channels steered through fades in
  // the other modes stay under the scalar loss rule.
  if (engagement_ == Engagement::all) out.lock = lock_report(end, cn0_.cn0_dbhz());
  return out;
}

SignalLockReport SteeredChannelController::lock_report(std::int64_t end_sample, double cn0_dbhz) const {
  SignalLockReport r;
  r.cn0_dbhz = cn0_dbhz;
  // Within the scalar loss time, or the longest integration (and a block) when that is longer.
  const LongIntegrationConfig& lc = cfg_.long_integration;
  const double hold_s = std::max(kLockHold_s, 1e-3 * std::max(lc.coherent_ms, lc.noncoherent_ms) + 0.02);
  r.locked = last_measurement_end_ && static_cast<double>(end_sample - *last_measurement_end_) <= hold_s * fs_;
  return r;
}

void SteeredChannelController::leave_long_integration() {
  long_mode_ = false;
  long_.reset();
  last_long_.reset();
}

void SteeredChannelController::choose_integration(const CorrelatorEpoch& e) {
  if (!cn0_.ready()) return;
  const double cn0 = cn0_.cn0_dbhz();
  const LongIntegrationConfig& lc = cfg_.long_integration;
  if (!long_mode_ && cn0 < lc.enter_below_dbhz) {
    long_mode_ = true;
    rate_window_.reset();
    spdlog::debug("PRN {:2d}: C/N0 {:.1f} dB-Hz: long integrations (coherent {} ms with data wipe-off)", e.prn, cn0,
                  lc.coherent_ms);
  } else if (long_mode_ && cn0 > lc.leave_above_dbhz) {
    leave_long_integration();
    rate_window_.reset();
    spdlog::debug("PRN {:2d}: C/N0 {:.1f} dB-Hz: back to {} ms integrations", e.prn, cn0,
                  static_cast<int>(std::lround(e.integration_s * 1e3)));
  }
}

void SteeredChannelController::phase_window_rate(DiscriminatorSample& d, std::int64_t end, double phase_cycles,
                                                 int samples) {
  if (const std::optional<WindowRate> r = rate_window_.add(end, phase_cycles, samples)) {
    d.rate_window_s = r->window_s;
    d.doppler_hz = r->doppler_hz;
    d.doppler_sample = r->mid_sample;
  }
}

void SteeredChannelController::short_sample(const CorrelatorEpoch& e, const ChannelView& view,
                                            const std::optional<double>& doppler) {
  const TrackingChannel& ch = view.channel;
  if (cfg_.carrier_phase_tracking)
    phase_correction_cycles_ = cfg_.carrier_phase_gain * costas_phase_error_cycles(e.prompt);
  const std::int64_t mid = e.first_sample + e.samples / 2;
  const std::optional<double> tt = transmit_time_sow(view.decoder, ch, mid);
  if (!tt) return;
  DiscriminatorSample d = sample_at(e, mid, *tt);
  d.code_error_chips = dll_code_error_chips(e.early, e.late, e.spacing_chips);
  // The phase is only as good as the Costas error is small: near its +-0.25 cycle range a
  // noise sample wraps it by half a cycle (5 Hz over a window). A large error means the
  // phase loop is stressed (the filter's Doppler still off after a start); then the
  // frequency discriminator serves.
  const double costas_cycles = costas_phase_error_cycles(e.prompt);
  if (cfg_.carrier_phase_tracking && e.pll_lock && std::abs(costas_cycles) < kMaxWindowPhaseError_cycles) {
    // Phase-locked: the mean frequency over adjoining windows of the carrier phase, a delta
    // range every window. The phase at an integration's end is the NCO's accumulated phase
    // (Costas corrections included) plus the Costas error still left: the loop's lag then
    // cancels, so the filter's own corrections to the NCO Doppler do not echo back into
    // the next window. The frequency discriminator across NCO updates is biased that way
    // (up to 0.6 m of position error on the aircraft circle). Without the phase loop the
    // accumulated phase would only repeat the filter's own commands.
    phase_window_rate(d, e.first_sample + e.samples, e.carrier_phase_cycles + costas_cycles, e.samples);
  } else {
    // Frequency tracking only (weak signals): the cross/dot discriminator between the two
    // adjoining integrations, referred to their common edge.
    rate_window_.reset();
    d.doppler_hz = doppler;
    d.doppler_sample = e.first_sample;
  }
  d.cn0_dbhz = e.cn0_dbhz;
  // The channel's estimate only once its window is full (a channel started by a guided
  // search is steered from its first integration).
  d.measurement = ch.lock_detector().ready() && e.cn0_dbhz >= cfg_.min_cn0_dbhz;
  queue(d, e.first_sample + e.samples, view);
}

void SteeredChannelController::long_sample(const SteeredIntegration& s, const ChannelView& view) {
  const CorrelatorEpoch& e = s.sums;
  const std::int64_t end = e.first_sample + e.samples;
  const double cn0 = cn0_.cn0_dbhz();
  // The replica's transmit time at the integration's end, from the NCO state it ended with
  // (the filter's code corrections inside it make extrapolating back from the channel's
  // present state wrong); the code error is the mean over the integration, which the
  // filter's small corrections hardly move from the end.
  const std::optional<double> tt = view.decoder.transmit_time_sow(e.code_period, e.code_phase_chips);
  std::optional<SteeredIntegration> previous = std::move(last_long_);
  last_long_.reset();
  if (!tt) return;
  DiscriminatorSample d = sample_at(e, end, *tt);
  d.cn0_dbhz = cn0;
  d.data_wiped = s.data_wiped;
  if (s.data_wiped) {
    d.code_error_chips = dll_code_error_chips(e.early, e.late, e.spacing_chips);
    // No data left: the four-quadrant phase, free of the Costas half-cycle ambiguity.
    const double phase_error_cycles = std::arg(e.prompt) / (2.0 * M_PI);
    if (cfg_.carrier_phase_tracking) phase_correction_cycles_ = cfg_.long_phase_gain * phase_error_cycles;
    const bool locked = cn0_.wiped_phase_lock_indicator() > kWipedPhaseLock;
    if (cfg_.carrier_phase_tracking && locked && std::abs(phase_error_cycles) < kMaxWindowPhaseError_cycles) {
      phase_window_rate(d, end, e.carrier_phase_cycles + phase_error_cycles, e.samples);
    } else {
      rate_window_.reset();
      if (previous && previous->sums.first_sample + previous->sums.samples == e.first_sample) {
        // The previous wiped integration adjoins: the NCO's mean frequency between the two
        // ends plus the prompts' phase advance between their centres.
        const CorrelatorEpoch& p = previous->sums;
        const double span_s = e.integration_s;
        const double centres_s = 0.5 * (p.integration_s + e.integration_s);
        d.doppler_hz = (e.carrier_phase_cycles - p.carrier_phase_cycles) / span_s +
                       std::arg(std::conj(p.prompt) * e.prompt) / (2.0 * M_PI * centres_s);
        d.doppler_sample = e.first_sample;
      }
    }
    last_long_ = s;
  } else {
    // Summed in power: early and late envelopes from their powers; no carrier phase.
    rate_window_.reset();
    d.code_error_chips = dll_code_error_chips(std::sqrt(s.early_power), std::sqrt(s.late_power), e.spacing_chips);
    d.piece_s = s.piece_s;
    if (s.frequency_pairs > 0) {
      // The carrier: the NCO's mean frequency over the integration (the filter's Doppler and
      // the bits' Costas corrections) plus the averaged cross/dot discriminator of its bits.
      d.doppler_hz = (e.carrier_phase_cycles - s.start_carrier_phase_cycles) / e.integration_s +
                     std::arg(s.frequency_product) / (2.0 * M_PI * s.piece_s);
      d.doppler_sample = e.first_sample + e.samples / 2;
      d.frequency_pairs = s.frequency_pairs;
    }
  }
  d.measurement = cn0_.signal_detected(kDetectionSigmas) &&
                  code_sigma_chips(cn0, e.integration_s, e.spacing_chips, d.piece_s) <=
                      code_sigma_chips(cfg_.min_cn0_dbhz, kReferenceIntegration_s, e.spacing_chips);
  spdlog::trace("t {:.2f} PRN {:2d}: {} ms {} C/N0 {:.1f} code {:+.3f} chips{}", end / fs_, e.prn,
                std::lround(e.integration_s * 1e3), s.data_wiped ? "wiped" : "non-coherent", cn0, d.code_error_chips,
                d.measurement ? "" : " (not a measurement)");
  queue(d, end, view);
}

void SteeredChannelController::queue(DiscriminatorSample d, std::int64_t end_sample, const ChannelView& view) {
  if (d.measurement) last_measurement_end_ = end_sample;
  d.ephemeris = *view.ephemeris;
  outbox_.push_back(std::move(d));
}

ChannelDecision SteeredChannelController::between_blocks(const ChannelView&) {
  ChannelDecision out;
  out.command = inbox_command_;
  if (inbox_release_) out.loss_detection = true;
  inbox_command_.reset();
  inbox_release_ = false;
  return out;
}

std::vector<DiscriminatorSample> SteeredChannelController::take_samples() {
  std::vector<DiscriminatorSample> samples;
  samples.swap(outbox_);
  return samples;
}

void SteeredChannelController::publish(const NcoCommand& command) {
  NcoCommand cmd = command;
  if (cfg_.carrier_phase_tracking && phase_correction_cycles_ != 0.0) {
    cmd.carrier_phase_correction_cycles = phase_correction_cycles_;
    applied_correction_cycles_ += phase_correction_cycles_;
    phase_correction_cycles_ = 0.0;
  }
  inbox_command_ = cmd;
}

void SteeredChannelController::publish_release() {
  steered_ = false;
  inbox_release_ = true;
}

void SteeredChannelController::release() {
  if (steered_) inbox_release_ = true;
  steered_ = false;
  outbox_.clear();
  leave_long_integration();
}

}  // namespace deepnav::aiding
