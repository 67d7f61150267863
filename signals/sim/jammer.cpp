#include "signals/sim/jammer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "signals/sim/bandlimited_noise.hpp"
#include "signals/sim/tone_generator.hpp"

namespace deepnav {
namespace {

[[noreturn]] void bad_field(const char* field, double value, const std::string& expected) {
  throw std::invalid_argument(fmt::format("jammer {} = {} is invalid: expected {}", field, value, expected));
}

void check_range(const char* field, double value, double lo, double hi, const std::string& unit) {
  if (!std::isfinite(value) || value < lo || value > hi)
    bad_field(field, value, fmt::format("{} to {} {}", lo, hi, unit));
}

void check_positive_bandwidth(const JammerConfig& c, double fs) {
  if (!std::isfinite(c.bandwidth_hz) || c.bandwidth_hz <= 0.0 || c.bandwidth_hz > fs)
    bad_field("bandwidth_hz", c.bandwidth_hz, fmt::format("> 0 and <= the sample rate {} Hz", fs));
}

std::int64_t time_to_sample(double t_s, double fs) { return static_cast<std::int64_t>(std::ceil(t_s * fs)); }

}  // namespace

JammerType parse_jammer_type(const std::string& name) {
  if (name == "cw") return JammerType::cw;
  if (name == "chirp") return JammerType::chirp;
  if (name == "wideband") return JammerType::wideband;
  if (name == "pulsed") return JammerType::pulsed;
  throw std::invalid_argument("unknown jammer type '" + name + "' (expected one of cw, chirp, wideband, pulsed)");
}

std::string to_string(JammerType type) {
  switch (type) {
    case JammerType::cw:
      return "cw";
    case JammerType::chirp:
      return "chirp";
    case JammerType::wideband:
      return "wideband";
    case JammerType::pulsed:
      return "pulsed";
  }
  return "?";
}

void validate_jammer(const JammerConfig& c, double fs, double if_hz) {
  if (!std::isfinite(fs) || fs <= 0.0) bad_field("sample rate", fs, "> 0 Hz");
  check_range("IF", if_hz, -0.5 * fs, 0.5 * fs, "Hz (within +-fs/2)");
  check_range("js_db", c.js_db, -50.0, 120.0, "dB");
  check_range("center_offset_hz", c.center_offset_hz, -0.5 * fs, 0.5 * fs, "Hz (within +-fs/2 of the IF)");
  if (!std::isfinite(c.start_s) || c.start_s < 0.0) bad_field("start_s", c.start_s, ">= 0 s");
  if (!std::isfinite(c.end_s) || (c.end_s > 0.0 && c.end_s <= c.start_s))
    bad_field("end_s", c.end_s, fmt::format("<= 0 (until the end) or > start_s = {} s", c.start_s));
  switch (c.type) {
    case JammerType::cw:
      break;
    case JammerType::chirp:
      check_positive_bandwidth(c, fs);
      if (!std::isfinite(c.sweep_period_s) || c.sweep_period_s * fs < 2.0)
        bad_field("sweep_period_s", c.sweep_period_s, fmt::format("> 0 and at least 2 samples ({} s)", 2.0 / fs));
      break;
    case JammerType::wideband:
      check_positive_bandwidth(c, fs);
      break;
    case JammerType::pulsed:
      if (!std::isfinite(c.duty_cycle) || c.duty_cycle <= 0.0 || c.duty_cycle > 1.0)
        bad_field("duty_cycle", c.duty_cycle, "in (0, 1]");
      if (!std::isfinite(c.pulse_rate_hz) || c.pulse_rate_hz <= 0.0 || c.pulse_rate_hz > 0.5 * fs)
        bad_field("pulse_rate_hz", c.pulse_rate_hz, fmt::format("> 0 and <= fs/2 = {} Hz", 0.5 * fs));
      if (!std::isfinite(c.bandwidth_hz) || c.bandwidth_hz < 0.0 || c.bandwidth_hz > fs)
        bad_field("bandwidth_hz", c.bandwidth_hz, fmt::format("0 (carrier pulses) or up to the sample rate {} Hz", fs));
      break;
  }
}

Jammer::Jammer(const JammerConfig& config, double sample_rate_hz, double if_hz, double cn0_ref_dbhz, std::uint64_t seed)
    : config_(config), sample_rate_hz_(sample_rate_hz) {
  validate_jammer(config, sample_rate_hz, if_hz);
  if (!std::isfinite(cn0_ref_dbhz)) bad_field("reference C/N0", cn0_ref_dbhz, "a finite value in dB-Hz");
  power_ = std::pow(10.0, 0.1 * cn0_ref_dbhz) * std::pow(10.0, 0.1 * config.js_db);
  first_on_sample_ = time_to_sample(config.start_s, sample_rate_hz);
  end_sample_ =
      config.end_s > 0.0 ? time_to_sample(config.end_s, sample_rate_hz) : std::numeric_limits<std::int64_t>::max();
  const double center_hz = if_hz + config.center_offset_hz;
  const bool noise =
      config.type == JammerType::wideband || (config.type == JammerType::pulsed && config.bandwidth_hz > 0.0);
  if (config.type == JammerType::chirp) {
    chirp_ = std::make_unique<ChirpGenerator>(center_hz, config.bandwidth_hz, config.sweep_period_s, sample_rate_hz);
  } else {
    tone_ = std::make_unique<ToneGenerator>(center_hz, sample_rate_hz);
  }
  if (noise) noise_ = std::make_unique<BandLimitedNoise>(config.bandwidth_hz, sample_rate_hz, seed);
}

Jammer::~Jammer() = default;
Jammer::Jammer(Jammer&&) noexcept = default;
Jammer& Jammer::operator=(Jammer&&) noexcept = default;

void Jammer::generate(std::span<std::complex<float>> out, std::int64_t first_sample) {
  const auto amplitude = static_cast<float>(std::sqrt(power_));
  if (chirp_) {
    chirp_->generate(out, first_sample, amplitude);
  } else if (noise_) {
    noise_->generate(out, first_sample, amplitude);
    // White noise stays white under a frequency shift; skip the mixer then.
    if (noise_->taps() > 1) tone_->mix(out, first_sample);
  } else {
    tone_->generate(out, first_sample, amplitude);
  }
}

// Pulse p is on for samples [ceil(p P), ceil(p P + d P)), P = fs / rate: both edges come
// from the pulse number alone, so gating is independent of block boundaries.
std::int64_t Jammer::pulse_start(std::int64_t pulse) const {
  return static_cast<std::int64_t>(std::ceil(static_cast<double>(pulse) * sample_rate_hz_ / config_.pulse_rate_hz));
}

std::int64_t Jammer::pulse_end(std::int64_t pulse) const {
  const double period = sample_rate_hz_ / config_.pulse_rate_hz;
  return static_cast<std::int64_t>(std::ceil(static_cast<double>(pulse) * period + config_.duty_cycle * period));
}

bool Jammer::pulse_on(std::int64_t sample) const {
  if (config_.type != JammerType::pulsed || config_.duty_cycle >= 1.0) return true;
  const double period = sample_rate_hz_ / config_.pulse_rate_hz;
  auto p = static_cast<std::int64_t>(std::floor(static_cast<double>(sample) / period));
  while (pulse_start(p) > sample) --p;
  while (pulse_start(p + 1) <= sample) ++p;
  return sample < pulse_end(p);
}

void Jammer::gate_pulses(std::span<std::complex<float>> out, std::int64_t first_sample) const {
  if (config_.type != JammerType::pulsed || config_.duty_cycle >= 1.0) return;
  const std::int64_t n = static_cast<std::int64_t>(out.size());
  const double period = sample_rate_hz_ / config_.pulse_rate_hz;
  // Pulse p0 starts at or before the block, so the off-intervals from p0 on cover the block.
  for (auto p = static_cast<std::int64_t>(std::floor(static_cast<double>(first_sample) / period)) - 1;; ++p) {
    const std::int64_t off_begin = pulse_end(p) - first_sample;
    if (off_begin >= n) break;
    const std::int64_t off_end = std::clamp(pulse_start(p + 1) - first_sample, std::int64_t{0}, n);
    const std::int64_t begin = std::clamp(off_begin, std::int64_t{0}, n);
    if (begin < off_end) std::fill(out.begin() + begin, out.begin() + off_end, std::complex<float>{});
  }
}

void Jammer::add_to(std::span<std::complex<float>> block, std::int64_t first_sample) {
  const std::int64_t block_end = first_sample + static_cast<std::int64_t>(block.size());
  const std::int64_t from = std::max(first_sample, first_on_sample_);
  const std::int64_t to = std::min(block_end, end_sample_);
  if (from >= to) return;
  const auto count = static_cast<std::size_t>(to - from);
  scratch_.resize(count);
  std::span<std::complex<float>> wave(scratch_.data(), count);
  generate(wave, from);
  gate_pulses(wave, from);
  auto* dst = reinterpret_cast<float*>(block.data() + (from - first_sample));
  const auto* src = reinterpret_cast<const float*>(scratch_.data());
  for (std::size_t k = 0; k < 2 * count; ++k) dst[k] += src[k];
}

}  // namespace deepnav
