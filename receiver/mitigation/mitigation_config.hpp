#pragma once
// Interference mitigation settings of the receiver front end: which technique runs
// and its parameters. Thresholds are in dB at this edge and converted to power ratios
// where they are used.
#include <string>
#include <vector>

namespace deepnav {

enum class MitigationMode {
  none,      ///< samples pass unchanged
  notch,     ///< adaptive complex notch filter (one narrowband interferer: CW, slow chirp)
  excision,  ///< frequency-domain excision of strong spectral lines (CW, chirp)
  blanking,  ///< pulse blanking (pulsed jammers)
  automatic  ///< blanking then excision: each acts only where it detects interference
};

/// "none", "notch", "excision", "blanking", "auto"; throws std::invalid_argument listing them otherwise.
MitigationMode parse_mitigation_mode(const std::string& name);
std::string to_string(MitigationMode mode);
/// Every accepted name, in the order above.
std::vector<std::string> mitigation_mode_names();

struct MitigationConfig {
  MitigationMode mode = MitigationMode::none;
  /// Excision: FFT length (power of two, 64..16384), frames overlap by half (Hann window).
  int excision_fft_size = 512;
  /// Excision: a bin is removed when its power exceeds the frame's noise floor (from the
  /// median bin) by this much. 12 dB: a noise-only bin exceeds it with probability 1e-7.
  double excision_threshold_db = 12.0;
  /// Blanking: a sample is zeroed when its power exceeds the noise estimate by this much
  /// (a complex Gaussian noise sample does so with probability exp(-10^(x/10)): 4.5e-5 at 10 dB).
  double blanking_threshold_db = 10.0;
  /// Blanking: samples also zeroed on each side of a detected one (pulse edges below threshold).
  int blanking_guard_samples = 4;
  /// Blanking: time constant of the noise-power estimate over unblanked samples.
  double blanking_noise_time_constant_s = 1e-3;
  /// Notch: pole contraction factor k_a in (0, 1): the notch's -3 dB width is about
  /// (1 - k_a) fs / pi (1.3 kHz at 0.999... here 0.99: 13 kHz at 4.092 Msps).
  double notch_pole_radius = 0.99;
  /// Notch: normalised adaptation step (NLMS) in (0, 1].
  double notch_step = 0.01;
};

/// Throws std::invalid_argument naming the field and the accepted range.
void validate_mitigation(const MitigationConfig& config, double sample_rate_hz);

}  // namespace deepnav
