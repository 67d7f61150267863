#include "receiver/acquisition/guided_search.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ins/gps_time.hpp"
#include "receiver/acquisition/acquisition.hpp"
#include "receiver/tracking/correlator.hpp"
#include "receiver/tracking/tracking_types.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kBit_s = 0.02;
constexpr double kCallSpacing_chips = 1.25;  // five taps 0.25 chip apart per call

double code_half_width(const GuidedSearchConfig& c, const SignalPrediction& p) {
  return std::max(c.min_code_half_width_chips, c.sigmas * p.code_sigma_chips);
}
double doppler_half_width(const GuidedSearchConfig& c, const SignalPrediction& p) {
  return std::max(c.min_doppler_half_width_hz, c.sigmas * p.doppler_sigma_hz);
}

/// Offset of a triangle's peak (the code correlation) from the sample `centre`, between its
/// neighbours `step` apart, limited to half a step.
double triangle_peak_offset(double minus, double centre, double plus, double step) {
  const double base = std::min(minus, plus);
  const double delta = centre > base ? 0.5 * step * (plus - minus) / (centre - base) : 0.0;
  return std::clamp(delta, -0.5 * step, 0.5 * step);
}

/// Frequency offset (Hz) of the signal from a bin whose amplitude is `centre`, from the
/// amplitude `neighbour` of the bin `step` Hz away (step signed: its side), on the
/// |sinc(f T)| response of a T-second coherent piece: the offset, towards the neighbour
/// (positive) or away from it, that gives their ratio. One neighbour is enough, so a peak
/// in an edge bin is refined too.
double sinc_peak_offset(double neighbour, double centre, double step, double piece_s) {
  const auto response = [&](double f) {
    const double x = M_PI * f * piece_s;
    return std::abs(x) < 1e-9 ? 1.0 : std::abs(std::sin(x) / x);
  };
  if (!(centre > 0.0)) return 0.0;
  const double ratio = std::min(neighbour / centre, 1.0);
  const double s = std::abs(step);
  // The ratio grows with the offset towards the neighbour: bisection on [-s, s/2].
  double lo = -s, hi = 0.5 * s;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    (response(s - mid) / response(mid) < ratio ? lo : hi) = mid;
  }
  return (step > 0.0 ? 1.0 : -1.0) * 0.5 * (lo + hi);
}

}  // namespace

bool cross_correlation_suspect(double found_doppler_hz, double found_cn0_dbhz, double tracked_doppler_hz,
                               double tracked_cn0_dbhz, double window_hz, double margin_db) {
  const double from_line_hz = std::remainder(found_doppler_hz - tracked_doppler_hz, 1000.0);
  return std::abs(from_line_hz) < window_hz && found_cn0_dbhz < tracked_cn0_dbhz - margin_db;
}

bool GuidedSearch::is_narrow(const GuidedSearchConfig& c, const SignalPrediction& p) {
  return code_half_width(c, p) <= c.max_code_half_width_chips &&
         doppler_half_width(c, p) <= c.max_doppler_half_width_hz;
}

GuidedSearch::GuidedSearch(const GuidedSearchConfig& config, const SignalPrediction& prediction, double sample_rate_hz,
                           double if_hz)
    : cfg_(config),
      prediction_(prediction),
      fs_(sample_rate_hz),
      if_hz_(if_hz),
      code_(&ca_code_chips(prediction.prn)),
      noise_code_(&ca_code_chips(noise_reference_prn(prediction.prn))),
      next_sample_(prediction.sample) {
  if (!(fs_ > 0.0)) throw std::invalid_argument("guided search: sample rate must be positive");
  if (!(cfg_.doppler_step_hz > 0.0 && cfg_.check_every_s >= kBit_s && cfg_.max_dwell_s >= cfg_.check_every_s &&
        cfg_.pfa > 0.0 && cfg_.pfa < 1.0))
    throw std::invalid_argument(
        "guided search: Doppler step, check interval, dwell or false-alarm probability out of range");
  if (!is_narrow(cfg_, prediction_))
    throw std::invalid_argument(
        fmt::format("guided search: PRN {} predicted to {:.1f} chips and {:.1f} Hz (1 sigma): not a narrow window",
                    prediction_.prn, prediction_.code_sigma_chips, prediction_.doppler_sigma_hz));
  // Calls cover [k * 1.25 - 0.5, k * 1.25 + 0.5] chips for k in [-K, K].
  const int k = static_cast<int>(std::ceil((code_half_width(cfg_, prediction_) - 0.5) / kCallSpacing_chips));
  calls_ = 2 * std::max(k, 0) + 1;
  const int b = static_cast<int>(std::ceil(doppler_half_width(cfg_, prediction_) / cfg_.doppler_step_hz - 0.5));
  for (int i = -b; i <= b; ++i) doppler_offsets_hz_.push_back(i * cfg_.doppler_step_hz);
  const std::size_t bins = doppler_offsets_hz_.size();
  piece_.assign(bins * static_cast<std::size_t>(calls_ * kTaps), 0.0);
  power_.assign(piece_.size(), 0.0);
  piece_noise_.assign(bins * static_cast<std::size_t>(calls_), 0.0);
  pieces_per_check_ = static_cast<int>(std::lround(cfg_.check_every_s / kBit_s));
  checks_total_ = static_cast<int>(std::ceil(cfg_.max_dwell_s / cfg_.check_every_s - 1e-9));
  bit_phase_s_ = std::fmod(prediction_.transmit_sow, kBit_s);
  bit_ = 0;
  piece_first_ = bit_edge_sample(0);
  piece_end_ = bit_edge_sample(1);
}

double GuidedSearch::dwell_s() const { return pieces_ * kBit_s; }

double GuidedSearch::cell_offset_chips(int c) const {
  const int centre = (calls_ * kTaps) / 2;
  return (c - centre) * kTapSpacing_chips;
}

std::int64_t GuidedSearch::bit_edge_sample(std::int64_t m) const {
  // Bit edges are the transmit times that are whole multiples of 20 ms; the signal's time
  // advances at 1 + Doppler / L1 seconds per second of samples.
  const double to_edge_s =
      (m * kBit_s - bit_phase_s_ + (bit_phase_s_ > 0.0 ? kBit_s : 0.0)) / (1.0 + prediction_.doppler_hz / gps::kL1_Hz);
  return prediction_.sample + static_cast<std::int64_t>(std::ceil(to_edge_s * fs_ - 1e-6));
}

std::int64_t GuidedSearch::first_bit_from(std::int64_t sample) const {
  std::int64_t m =
      std::max<std::int64_t>(0, static_cast<std::int64_t>((sample - prediction_.sample) / (kBit_s * fs_)) - 1);
  while (bit_edge_sample(m) < sample) ++m;
  return m;
}

double GuidedSearch::doppler_at(double doppler_offset_hz, std::int64_t sample) const {
  const double dt = static_cast<double>(sample - prediction_.sample) / fs_;
  return prediction_.doppler_hz + doppler_offset_hz + prediction_.doppler_rate_hzps * dt;
}

double GuidedSearch::code_chips_at(double offset_chips, double doppler_offset_hz, std::int64_t sample) const {
  const double dt = static_cast<double>(sample - prediction_.sample) / fs_;
  const double start_chips = std::fmod(prediction_.transmit_sow, 1e-3) * gps::kCodeRate_cps;
  // The code follows the carrier's Doppler (its rate included).
  const double doppler_cycles =
      (prediction_.doppler_hz + doppler_offset_hz) * dt + 0.5 * prediction_.doppler_rate_hzps * dt * dt;
  return start_chips + offset_chips + gps::kCodeRate_cps * dt + doppler_cycles * gps::kCodeRate_cps / gps::kL1_Hz;
}

void GuidedSearch::add(const SampleBlock& block) {
  if (outcome_ != Outcome::searching) return;
  const std::int64_t block_end = block.first_sample_index + static_cast<std::int64_t>(block.samples.size());
  if (block.first_sample_index > next_sample_ && piece_started_) {
    // Samples were lost inside the piece: it cannot be whole; start again at the next bit.
    std::fill(piece_.begin(), piece_.end(), 0.0);
    std::fill(piece_noise_.begin(), piece_noise_.end(), 0.0);
    piece_started_ = false;
  }
  if (block.first_sample_index > piece_first_ && !piece_started_) {
    bit_ = first_bit_from(block.first_sample_index);
    piece_first_ = bit_edge_sample(bit_);
    piece_end_ = bit_edge_sample(bit_ + 1);
  }
  std::int64_t idx = std::max(next_sample_, block.first_sample_index);
  while (idx < block_end && outcome_ == Outcome::searching) {
    if (idx < piece_first_) {
      idx = std::min(piece_first_, block_end);
      continue;
    }
    const std::int64_t n = std::min(piece_end_, block_end) - idx;
    correlate_span(block, idx, static_cast<int>(n));
    piece_started_ = true;
    idx += n;
    if (idx == piece_end_) finish_piece();
  }
  next_sample_ = std::max(next_sample_, block_end);
}

void GuidedSearch::correlate_span(const SampleBlock& block, std::int64_t first, int n) {
  const auto offset = static_cast<std::size_t>(first - block.first_sample_index);
  CorrelatorInput input{block.samples.data() + offset};
  if (block.planar.size() == 2 * block.samples.size()) {
    input.i = block.planar.data() + offset;
    input.q = block.planar.data() + block.samples.size() + offset;
  }
  const std::int64_t mid = (piece_first_ + piece_end_) / 2;
  for (std::size_t bin = 0; bin < doppler_offsets_hz_.size(); ++bin) {
    const double df = doppler_offsets_hz_[bin];
    const double doppler = doppler_at(df, mid);
    const double code_step = gps::kCodeRate_cps * (1.0 + doppler / gps::kL1_Hz) / fs_;
    for (int call = 0; call < calls_; ++call) {
      // The call's prompt sits on its middle tap.
      const double prompt_offset = cell_offset_chips(call * kTaps + kTaps / 2);
      CorrelatorSpan span;
      // Non-coherent pieces: the carrier phase only has to run on within the piece.
      span.carrier_phase_cycles = (if_hz_ + doppler) * static_cast<double>(first - piece_first_) / fs_;
      span.carrier_step_cycles = (if_hz_ + doppler) / fs_;
      const double chips = code_chips_at(prompt_offset, df, first);
      span.code_phase_chips = chips - std::floor(chips / gps::kCodeLength_chips) * gps::kCodeLength_chips;
      span.code_step_chips = code_step;
      span.spacing_chips = 2.0 * kTapSpacing_chips;
      span.very_spacing_chips = 4.0 * kTapSpacing_chips;
      span.magnitude_bits = block.magnitude_bits;
      const CorrelatorSums s = correlate(input, n, span, *code_, *noise_code_);
      // Taps in order of code offset: very-late (-0.5), late, prompt, early, very-early (+0.5).
      std::complex<double>* cell =
          &piece_[(bin * static_cast<std::size_t>(calls_) + static_cast<std::size_t>(call)) * kTaps];
      cell[0] += s.very_late;
      cell[1] += s.late;
      cell[2] += s.prompt;
      cell[3] += s.early;
      cell[4] += s.very_early;
      piece_noise_[bin * static_cast<std::size_t>(calls_) + static_cast<std::size_t>(call)] += s.noise;
    }
  }
}

void GuidedSearch::finish_piece() {
  for (std::size_t i = 0; i < piece_.size(); ++i) power_[i] += std::norm(piece_[i]);
  for (const std::complex<double>& n : piece_noise_) noise_power_sum_ += std::norm(n);
  noise_terms_ += static_cast<long>(piece_noise_.size());
  std::fill(piece_.begin(), piece_.end(), 0.0);
  std::fill(piece_noise_.begin(), piece_noise_.end(), 0.0);
  piece_started_ = false;
  ++pieces_;
  ++bit_;
  piece_first_ = piece_end_;
  piece_end_ = bit_edge_sample(bit_ + 1);
  if (pieces_ % pieces_per_check_ == 0) check();
}

void GuidedSearch::check() {
  ++checks_made_;
  const double noise = noise_power_sum_ / static_cast<double>(noise_terms_);
  const auto best = static_cast<std::size_t>(std::max_element(power_.begin(), power_.end()) - power_.begin());
  const double statistic = power_[best] / noise;
  const double threshold = acquisition_threshold(pieces_, static_cast<double>(power_.size()), cfg_.pfa / checks_total_);
  if (statistic < threshold) {
    if (checks_made_ >= checks_total_) outcome_ = Outcome::not_found;
    return;
  }
  const std::size_t per_bin = static_cast<std::size_t>(calls_ * kTaps);
  const std::size_t bin = best / per_bin;
  const int c = static_cast<int>(best % per_bin);
  // Mean power per piece above the noise: the signal's power at each cell.
  const auto signal_power = [&](std::size_t b, int cell) {
    return std::max(power_[b * per_bin + static_cast<std::size_t>(cell)] / pieces_ - noise, 0.0);
  };
  GuidedDetection d;
  d.prn = prediction_.prn;
  d.code_offset_chips = cell_offset_chips(c);
  if (c > 0 && c + 1 < static_cast<int>(per_bin))
    d.code_offset_chips += triangle_peak_offset(std::sqrt(signal_power(bin, c - 1)), std::sqrt(signal_power(bin, c)),
                                                std::sqrt(signal_power(bin, c + 1)), kTapSpacing_chips);
  d.doppler_offset_hz = doppler_offsets_hz_[bin];
  // Refined from the stronger neighbouring bin.
  const double below = bin > 0 ? signal_power(bin - 1, c) : -1.0;
  const double above = bin + 1 < doppler_offsets_hz_.size() ? signal_power(bin + 1, c) : -1.0;
  if (std::max(below, above) >= 0.0) {
    const bool up = above >= below;
    d.doppler_offset_hz += sinc_peak_offset(std::sqrt(up ? above : below), std::sqrt(signal_power(bin, c)),
                                            up ? cfg_.doppler_step_hz : -cfg_.doppler_step_hz, kBit_s);
  }
  const double snr = signal_power(bin, c) / noise;  // per 20 ms piece: C/N0 T
  d.cn0_dbhz = snr > 0.0 ? 10.0 * std::log10(snr / kBit_s) : 0.0;
  d.statistic = statistic;
  d.threshold = threshold;
  d.dwell_s = dwell_s();
  detection_ = d;
  outcome_ = Outcome::found;
}

GuidedStart GuidedSearch::start_at(std::int64_t sample, int channel) const {
  if (!detection_) throw std::logic_error("guided search: no signal found to start a channel on");
  const GuidedDetection& d = *detection_;
  const double chips = code_chips_at(d.code_offset_chips, d.doppler_offset_hz, sample);
  const double periods = std::floor(chips / gps::kCodeLength_chips);
  GuidedStart s;
  s.channel.prn = prediction_.prn;
  s.channel.channel = channel;
  s.channel.sample_index = sample;
  s.channel.doppler_hz = doppler_at(d.doppler_offset_hz, sample);
  s.channel.code_phase_chips = chips - periods * gps::kCodeLength_chips;
  // Code period 0 of the channel starts `periods` periods after the one the prediction's
  // sample lies in, whose transmit time is the predicted one less its code phase.
  const double period0_ms =
      std::round((prediction_.transmit_sow - std::fmod(prediction_.transmit_sow, 1e-3)) * 1e3) + periods;
  double sow = period0_ms * 1e-3;
  if (sow >= kSecondsPerWeek) sow -= kSecondsPerWeek;
  s.period0_transmit_sow = sow;
  // Data bits start at transmit times that are multiples of 20 ms.
  const auto ms = static_cast<std::int64_t>(period0_ms);
  s.channel.bit_edge_period = (20 - ms % 20) % 20;
  return s;
}

}  // namespace deepnav
