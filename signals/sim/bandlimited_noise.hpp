#pragma once
// Unit-power complex Gaussian noise confined to |f| < B/2 at complex baseband, as a
// function of (seed, absolute sample index).
//
// Shaping filter: a linear-phase FIR lowpass, Kaiser-windowed sinc with the cutoff
// (-6 dB point) at B/2, designed for 60 dB stopband (beta = 5.65) with a transition band
// 0.25 B wide, which needs N ~ 3.62 fs / (0.25 B) = 14.5 fs / B taps (Kaiser's formula).
// The response is flat to < 0.01 dB up to 0.375 B from the centre and >= 60 dB down
// beyond 0.625 B. Taps are capped at kMaxTaps, so bands narrower than about fs / 140
// get a proportionally wider transition. The taps are scaled so that sum h^2 = 1: the
// output power is exactly the input power whatever the filter. For B >= fs the noise is
// white and no filter runs.
#include <complex>
#include <cstdint>
#include <span>
#include <vector>

#include "signals/sim/indexed_noise.hpp"

namespace deepnav {

/// Windowed-sinc lowpass taps (odd length, unit energy) for a two-sided bandwidth B.
std::vector<float> design_noise_shaping_taps(double bandwidth_hz, double sample_rate_hz);

class BandLimitedNoise {
 public:
  static constexpr int kMaxTaps = 2047;

  BandLimitedNoise(double bandwidth_hz, double sample_rate_hz, std::uint64_t seed);
  /// out[k] = sqrt(power) * noise(first_sample + k), with E|noise|^2 = 1.
  void generate(std::span<std::complex<float>> out, std::int64_t first_sample, float amplitude);
  int taps() const { return static_cast<int>(taps_.size()); }

 private:
  void filter(float* y, const float* x, std::int64_t n) const;
  std::vector<float> taps_;
  IndexedNoise noise_i_, noise_q_;
  std::vector<float> raw_i_, raw_q_, out_i_, out_q_;  ///< raw: taps-1 history then the block
  std::int64_t next_sample_ = 0;                      ///< raw history is valid for this start
  bool history_valid_ = false;
};

}  // namespace deepnav
