#include "aiding/steered_channel_controller.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include "receiver/nav_decoder.hpp"
#include "receiver/tracking_channel.hpp"
#include "receiver/tracking_loops.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kRateWindow_s = 0.1;                // phase-locked rate: adjoining windows of the mean frequency
constexpr double kMaxWindowPhaseError_cycles = 0.1;  // a window's ends: Costas error within +-36 deg

}  // namespace

bool can_steer(bool bit_synced, ChannelState state, bool decoder_synchronised, bool has_ephemeris) {
  return bit_synced && state != ChannelState::lost && decoder_synchronised && has_ephemeris;
}

SteeredChannelController::SteeredChannelController(const UltraTightConfig& config, double sample_rate_hz,
                                                   const Engagement& engagement)
    : cfg_(config), fs_(sample_rate_hz), engagement_(engagement) {}

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
    rate_window_start_.reset();  // a window must lie inside one steered stretch
    return out;
  }
  out.owns_epoch = true;
  if (!was_steered) {
    steered_ = true;
    out.loss_detection = false;
    spdlog::debug("PRN {:2d}: steered by the navigation filter", e.prn);
  }
  if (cfg_.carrier_phase_tracking) phase_correction_cycles_ = cfg_.carrier_phase_gain * costas_phase_error_cycles(e.prompt);
  const std::int64_t mid = e.first_sample + e.samples / 2;
  const std::optional<double> tt = transmit_time_sow(view.decoder, ch, mid);
  if (!tt) return out;
  DiscriminatorSample d;
  d.prn = e.prn;
  d.mid_sample = mid;
  d.replica_transmit_sow = *tt;
  d.spacing_chips = e.spacing_chips;
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
    const double phase_cycles = e.carrier_phase_cycles + costas_cycles;
    const auto window = static_cast<std::int64_t>(std::llround(kRateWindow_s * fs_));
    if (rate_window_start_ && end - *rate_window_start_ >= window - e.samples / 2) {
      d.rate_window_s = static_cast<double>(end - *rate_window_start_) / fs_;
      d.doppler_hz = (phase_cycles - rate_window_start_cycles_) / d.rate_window_s;
      d.doppler_sample = (*rate_window_start_ + end) / 2;
    }
    if (!rate_window_start_ || d.doppler_hz) {
      rate_window_start_ = end;
      rate_window_start_cycles_ = phase_cycles;
    }
  } else {
    // Frequency tracking only (weak signals): the cross/dot discriminator between the two
    // adjoining integrations, referred to their common edge.
    rate_window_start_.reset();
    d.doppler_hz = doppler;
    d.doppler_sample = e.first_sample;
  }
  d.cn0_dbhz = e.cn0_dbhz;
  d.integration_s = e.integration_s;
  d.ephemeris = *view.ephemeris;
  outbox_.push_back(d);
  return out;
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
}

}  // namespace deepnav::aiding
