#pragma once
// FFT parallel code-phase search for GPS L1 C/A (FFTW, single precision).
//
// For every Doppler bin the input is mixed to baseband and Fourier transformed once;
// each PRN then costs one product with its precomputed code spectrum and one inverse
// FFT per coherent block. Blocks of `coherent_ms` are summed non-coherently
// (|.|^2). Detection statistic: the peak cell divided by the mean cell power of the
// search grid away from the peak; under noise alone each cell of a K-block sum is
// Gamma(K, 1) distributed after that normalisation, so the threshold for a false-alarm
// probability Pfa over the M cells searched solves Q(K, gamma) = 1 - (1 - Pfa)^(1/M).
// The strongest cell of a detected PRN is then refined in Doppler (a finer search at the
// peak's code phase, at the sample rate) and in delay (parabolic interpolation between
// lags); a PRN below the threshold keeps its coarse bin.
//
// FFT size: a coherent block of n samples whose length has a prime factor above 7
// (4.092 Msps: 4092 = 4 * 3 * 11 * 31) is stretched to the next size made of 2, 3, 5 and 7
// (4096) by repeating the nearest sample, and the replica is drawn at the stretched rate:
// the transforms run about five times faster, at the cost of a timing error that ramps
// through +-1/2 sample across the block (about 0.2 dB of peak power at 4 samples per chip,
// 0.4 dB at 2). Delays are converted back to samples of the input.
#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "receiver/sources/sample_source.hpp"

namespace deepnav {

/// Limits of a search: non-coherent blocks (each is held in memory) and the sample rate.
inline constexpr int kMaxNoncoherent = 1000;
inline constexpr double kMaxAcquisitionSampleRate_hz = 2.0e8;

struct AcquisitionConfig {
  double sample_rate_hz = 4.092e6;
  double if_hz = 0.0;
  int coherent_ms = 1;   ///< 1..10
  int noncoherent = 10;  ///< coherent blocks summed (limited by the samples given)
  double doppler_max_hz = 5000.0;
  double doppler_step_hz = 0.0;  ///< 0: 2 / (3 T_coh)
  /// False-alarm probability per PRN search under white noise. Real captures with strong
  /// satellites have heavier floors (their cross-correlation); at 1e-3 the bundled captures
  /// show false detections, at 1e-5 none.
  double pfa = 1e-5;
  /// A detection this far (dB) below the strongest one in the same search cannot be told
  /// from that satellite's cross-correlation (C/A worst case about -21 dB with a Doppler offset,
  /// plus the noise peak's bias on the weak estimate) and is rejected.
  double cross_correlation_margin_db = 18.0;
  std::vector<int> prns;  ///< empty: all 32
};

struct AcquisitionResult {
  int prn = 0;
  bool detected = false;
  double doppler_hz = 0.0;        ///< refined
  double delay_samples = 0.0;     ///< where the code epoch starts after the first sample, in [0, samples per ms)
  double code_phase_chips = 0.0;  ///< code phase at the first sample, in [0, 1023)
  double cn0_dbhz = 0.0;          ///< from the peak-to-noise ratio (coherent SNR / T)
  double statistic = 0.0;         ///< normalised peak (see above)
  double threshold = 0.0;
  bool cross_correlation_suspect = false;  ///< over the threshold but rejected (see the config)
};

/// Why `samples` cannot be IF samples of a GPS front end, or empty when they can be: a
/// front end delivers noise (the satellites lie below it) around zero, so constant samples,
/// or a mean further from zero than the samples spread (a text file read as int8, unsigned
/// samples read as signed), mean a wrong file or --format. `real`: only I carries samples.
std::string if_sample_problem(std::span<const Sample> samples, bool real);

class Acquisition {
 public:
  /// Makes the FFTW plans (once per object; objects may be made in several threads at once).
  explicit Acquisition(AcquisitionConfig config);
  ~Acquisition();
  Acquisition(const Acquisition&) = delete;
  Acquisition& operator=(const Acquisition&) = delete;

  /// Samples needed for the full search (coherent_ms * noncoherent ms).
  std::int64_t samples_needed() const;
  /// Searches every configured PRN in `samples` (the first of them defines delay 0).
  /// Fewer samples than samples_needed() shorten the non-coherent sum; fewer than one
  /// coherent block throw std::invalid_argument.
  std::vector<AcquisitionResult> search(std::span<const Sample> samples);
  /// The same for `prns`, a subset of the configured ones (a receiver searching again for
  /// the satellites it does not track keeps one object, its plans and its buffers).
  std::vector<AcquisitionResult> search(std::span<const Sample> samples, const std::vector<int>& prns);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Q(K, x) = P(Gamma(K, 1) > x) for integer K (regularized upper incomplete gamma).
double gamma_upper_tail(int k, double x);
/// Detection threshold on the normalised statistic for `cells` cells of K-block sums.
double acquisition_threshold(int k, double cells, double pfa);

}  // namespace deepnav
