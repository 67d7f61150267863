#pragma once
// The receiver front end's analogue-to-digital stage: an automatic gain control that
// loads the quantizer optimally, and a uniform mid-rise quantizer packed into the IF
// sample formats.
//
// Quantizer levels: b bits give the 2^b odd integer levels +-1, +-3, ..., +-(2^b - 1)
// (1 bit: the sign, +-1); thresholds sit at the even integers in between and inputs
// beyond the outer thresholds saturate. The levels are stored as they are when they fit
// the container (a 2-bit ADC written as ibyte holds {-3, -1, 1, 3}, as PocketSDR
// captures do). When the ADC uses the container's full width (8 bits in int8, 16 bits in
// int16) the odd levels do not fit, and the stored value is the two's-complement code
// (level - 1) / 2 in [-2^(b-1), 2^(b-1) - 1], as 8-bit SDR front ends write it (a level
// scaled by 1/2 with a -1/2 LSB offset). The unsigned format cu8 stores (level + 255) / 2,
// so an 8-bit ADC fills 0..255 around 127.5 as an RTL-SDR does. Packed formats store the
// odd levels as B-bit codes (signals/sample_packing.hpp); an ADC of fewer bits than B uses
// the inner codes.
//
// Optimum loading: the AGC scales the input so that each component (I, Q or the real
// sample) has the RMS that minimises the quantisation noise of a Gaussian input for a
// uniform quantizer (J. Max, "Quantizing for minimum distortion", IRE Trans. IT-6, 1960,
// Table II): step/sigma = 1.596 (1 bit), 0.9957 (2), 0.5860 (3), 0.3352 (4), 0.1881 (5),
// 0.1041 (6), 0.0569 (7), 0.0308 (8); beyond 8 bits full scale = +-4 sigma. With a step
// of 2 level units the target RMS is 2 / (step/sigma): 2.009 for 2 bits, i.e. the
// thresholds +-2 sit at 0.996 sigma, the known 2-bit optimum (0.55 dB correlation loss).
#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>

#include "signals/sample_format.hpp"

namespace deepnav {

struct AdcConfig {
  int bits = 2;  ///< 1..8 for ibyte/byte/cu8, 1..16 for ishort, 0..16 for gr_complex (0 = no quantization), 1..B packed
  double agc_target_rms = 0.0;        ///< per-component RMS at the quantizer input, in level units; 0 = optimum
  bool agc_enabled = true;            ///< false: fixed_gain instead of the AGC
  double agc_time_constant_s = 1e-3;  ///< time constant of the AGC's power estimate
  double fixed_gain = 1.0;            ///< gain applied when the AGC is disabled
};

/// Optimum per-component RMS (level units) for a b-bit quantizer; 1.0 for b = 0.
double optimum_quantizer_rms(int bits);
/// Throws std::invalid_argument naming the field (adc.bits, adc.agc_target_rms, ...) when
/// the settings do not fit the format or are out of range.
void validate_adc(const AdcConfig& config, const SampleFormat& format);

/// Feed-forward AGC. The power of the whole input (signals, noise, jammers) is measured
/// over windows of kWindow samples aligned to absolute sample indices and smoothed by a
/// first-order filter with the configured time constant; each window is scaled by the gain
/// target_rms / sqrt(power estimate) set before the window (causal, as a hardware AGC
/// whose loop runs every kWindow samples). The first window initialises the estimate.
class Agc {
 public:
  static constexpr int kWindow = 64;
  Agc(const AdcConfig& config, double sample_rate_hz);

  bool initialized() const { return power_ >= 0.0; }
  /// Starts the estimate at this per-component power (the first samples seen).
  void initialize(double power);
  /// Gain for the current window (fixed_gain when the AGC is disabled).
  float gain() const { return gain_; }
  /// Per-component power estimate, input units.
  double power_estimate() const { return power_; }
  /// Adds part of the current window (sum of squares over `values` components); when
  /// `window_done`, the window's power enters the estimate and the gain is updated.
  void accumulate(double sum_squares, std::size_t values, bool window_done);

 private:
  void set_gain();
  bool enabled_;
  double target_rms_, fixed_gain_, alpha_;
  double power_ = -1.0;  ///< < 0 until initialised
  double window_sum_ = 0.0;
  std::size_t window_values_ = 0;
  float gain_;
};

/// The odd levels of x[k] * gain (k < n) for a b-bit quantizer.
void quantize_levels(const float* x, std::size_t n, float gain, int bits, std::int16_t* out);

/// Quantizes x[k] * gain (k < n values, interleaved I/Q or real) with the given bits and
/// packs the results into `out` in the container of `format` (n values of 1, 2 or 4 bytes;
/// a packed format: n must fill whole words, in time order as the layout has them).
void quantize_pack(const float* x, std::size_t n, float gain, int bits, const SampleFormat& format, std::byte* out);

/// Decodes packed values back to level units (inverse of the storage rule above), for
/// readers and tests: out must hold n values (a packed format: whole words of them).
void unpack_levels(const std::byte* in, std::size_t n, int bits, const SampleFormat& format, float* out);

}  // namespace deepnav
