#pragma once
// A synthetic single-satellite C/A signal for the tracking tests: Doppler ramp, data bits
// (seeded random or a real LNAV stream), white noise with N0 = 1, int16 samples, produced
// block by block so long runs need little memory.
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/gaussian_noise.hpp"
#include "signals/sim/satellite_signal_kernel.hpp"

namespace deepnav::testing {

struct ChannelSignalSpec {
  double fs_hz = 2.5e6;
  int prn = 5;
  double cn0_dbhz = 45.0;
  double doppler0_hz = 2000.0;
  double doppler_rate_hzps = 1.0;
  double code0_chips = 100.3;  ///< unwrapped code phase at t = 0 (chips of period 0)
  double carrier0_cycles = 0.3;
  std::uint64_t seed = 3;
  /// From this time on the C/N0 is cn0_after_dbhz (a fade); negative: never.
  double fade_at_s = -1.0;
  double cn0_after_dbhz = 0.0;
  /// Data bit (+1 / -1) of the signal's bit k (code periods 20k .. 20k + 19); empty: random.
  std::function<int(std::int64_t)> bit;
};

class ChannelSignal {
 public:
  explicit ChannelSignal(ChannelSignalSpec spec) : s_(std::move(spec)), noise_(s_.seed + 17) {}

  const ChannelSignalSpec& spec() const { return s_; }
  double doppler_hz(double t) const { return s_.doppler0_hz + s_.doppler_rate_hzps * t; }
  /// Unwrapped code phase (chips) of the signal arriving at time t.
  double code_chips(double t) const {
    const double k = gps::kCodeRate_cps / gps::kL1_Hz;  // code Doppler follows the carrier's
    return s_.code0_chips + gps::kCodeRate_cps * t + k * (s_.doppler0_hz * t + 0.5 * s_.doppler_rate_hzps * t * t);
  }
  double carrier_cycles(double t) const {
    return s_.carrier0_cycles + s_.doppler0_hz * t + 0.5 * s_.doppler_rate_hzps * t * t;
  }
  int samples_per_ms() const { return static_cast<int>(std::lround(s_.fs_hz / 1000.0)); }

  /// The next `ms` milliseconds of samples (fs must be a multiple of 1 kHz).
  SampleBlock next(int ms) {
    const int per_ms = samples_per_ms();
    const std::size_t total = static_cast<std::size_t>(per_ms) * static_cast<std::size_t>(ms);
    i_.assign(total, 0.0f);
    q_.assign(total, 0.0f);
    scratch_.resize(static_cast<std::size_t>(per_ms));
    for (int m = 0; m < ms; ++m) {
      const double t = static_cast<double>(ms_done_ + m) * 1e-3;
      const double cn0 = (s_.fade_at_s >= 0.0 && t >= s_.fade_at_s) ? s_.cn0_after_dbhz : s_.cn0_dbhz;
      const float a = static_cast<float>(std::pow(10.0, cn0 / 20.0));
      add_millisecond(ms_done_ + m, i_.data() + static_cast<std::size_t>(m) * per_ms,
                      q_.data() + static_cast<std::size_t>(m) * per_ms, a);
    }
    const float sigma = static_cast<float>(std::sqrt(s_.fs_hz / 2.0));
    noise_.add_real(i_, sigma);
    noise_.add_real(q_, sigma);
    const float scale = 64.0f / sigma;  // int16 with the noise at 64 counts RMS
    SampleBlock b;
    b.first_sample_index = static_cast<std::int64_t>(ms_done_) * per_ms;
    b.samples.resize(total);
    for (std::size_t k = 0; k < total; ++k)
      b.samples[k] = {static_cast<std::int16_t>(std::lround(i_[k] * scale)),
                      static_cast<std::int16_t>(std::lround(q_[k] * scale))};
    ms_done_ += ms;
    return b;
  }

 private:
  int bit_sign(std::int64_t bit) const {
    if (s_.bit) return s_.bit(bit);
    std::mt19937_64 rng(s_.seed * 1000003 + static_cast<std::uint64_t>(bit));
    return (rng() & 1) ? -1 : 1;
  }

  void add_millisecond(std::int64_t m, float* i, float* q, float a) {
    const int per_ms = samples_per_ms();
    const double t0 = m * 1e-3, t1 = (m + 1) * 1e-3;
    const double c0 = code_chips(t0), c1 = code_chips(t1);
    const double p0 = carrier_cycles(t0), p1 = carrier_cycles(t1);
    const double step = (c1 - c0) / per_ms, carrier_step = (p1 - p0) / per_ms;
    // Split at the code period edge: the data bit changes on 20-period boundaries.
    int first = 0;
    while (first < per_ms) {
      const double chips = c0 + first * step;
      const double period = std::floor(chips / 1023.0);
      const int last = std::min(per_ms, static_cast<int>(std::ceil(((period + 1) * 1023.0 - c0) / step)));
      const int count = std::max(1, last - first);
      SignalSegment sg;
      sg.code_phase_chips = chips - period * 1023.0;
      sg.code_step_chips = step;
      sg.carrier_phase_cycles = p0 + first * carrier_step;
      sg.carrier_step_cycles = carrier_step;
      sg.amplitude = a * static_cast<float>(bit_sign(static_cast<std::int64_t>(std::floor(period / 20.0))));
      add_satellite_segment(i + first, q + first, count, sg, ca_code_chips(s_.prn), scratch_.data());
      first += count;
    }
  }

  ChannelSignalSpec s_;
  GaussianNoise noise_;
  std::int64_t ms_done_ = 0;
  std::vector<float> i_, q_, scratch_;
};

}  // namespace deepnav::testing
