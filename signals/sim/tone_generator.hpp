#pragma once
// Unit-amplitude complex tones whose phase is a function of the absolute sample index
// (no floating-point time accumulated across blocks): a constant-frequency tone and a
// linear sawtooth frequency sweep (chirp).
#include <complex>
#include <cstdint>
#include <span>
#include <vector>

namespace deepnav {

/// exp(j 2 pi f n / fs). The phase step is a 64-bit fixed-point fraction of a cycle, so
/// the phase of sample n is (n * step) mod 2^64 exactly; the frequency is quantised to
/// fs / 2^64. Within a block the tone is an exact anchor phasor per 1024 samples times a
/// precomputed table of exp(j 2 pi f m / fs), m < 1024.
class ToneGenerator {
 public:
  ToneGenerator(double frequency_hz, double sample_rate_hz);
  /// out[k] = amplitude * exp(j 2 pi f (first_sample + k) / fs).
  void generate(std::span<std::complex<float>> out, std::int64_t first_sample, float amplitude) const;
  /// out[k] *= exp(j 2 pi f (first_sample + k) / fs)  (frequency shift of a baseband block).
  void mix(std::span<std::complex<float>> out, std::int64_t first_sample) const;

 private:
  static constexpr int kTable = 1024;
  std::complex<double> anchor(std::int64_t sample) const;
  std::uint64_t step_ = 0;  ///< cycles per sample in units of 2^-64
  std::vector<float> table_re_, table_im_;
};

/// Linear sawtooth sweep from f_low = f_c - B/2 to f_high = f_c + B/2 over each period T,
/// then back to f_low. Sweep k starts at t_k = k T (sample 0 is t = 0); the phase is the
/// integral of the frequency, continuous across sweep restarts:
///   phi(t) = k f_c T + f_low tau + B tau^2 / (2 T),   tau = t - k T.
class ChirpGenerator {
 public:
  ChirpGenerator(double center_hz, double bandwidth_hz, double period_s, double sample_rate_hz);
  /// out[k] = amplitude * exp(j 2 pi phi((first_sample + k) / fs)).
  void generate(std::span<std::complex<float>> out, std::int64_t first_sample, float amplitude) const;
  /// Instantaneous frequency at sample n (Hz), for tests and reports.
  double frequency_hz(std::int64_t sample) const;

 private:
  /// Phase in cycles (reduced to [0, 1)) and sweep-relative time of sample n.
  double phase_cycles(std::int64_t sweep, double tau_s) const;
  std::int64_t sweep_of(std::int64_t sample) const;
  std::int64_t sweep_start_sample(std::int64_t sweep) const;  ///< first sample with t >= k T
  double f_low_hz_, bandwidth_hz_, period_s_, fs_;
  double sweep_phase_frac_;  ///< frac(f_c T): phase gained over one full sweep
};

}  // namespace deepnav
