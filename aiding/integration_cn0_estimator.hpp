#pragma once
// C/N0 of a steered channel from integrations of any length, coherent or not: the estimate
// the aided modes judge weak signals by.
//
// The channel's own estimate (receiver/tracking/lock_detectors) averages a fixed number of its
// 10 ms integrations; at 12 dB-Hz their post-integration SNR is 0.16 and a 0.2 s window of
// them reads 0 most of the time. Here every integration, whatever it was (a 10 ms channel
// integration, a 200 ms one with the data wiped off, or K 20 ms bits summed in power),
// enters with what its power is expected to be:
//   E[sum |P_k|^2] = C sum T_k^2 + n sum T_k,
// with C the signal power and n the noise density in correlator units, so over a window
//   C = (sum |P_k|^2 - n sum T_k) / sum T_k^2,   C/N0 = C / n.
// n comes from the channel's noise correlator (an unused PRN on the same carrier):
// E|N|^2 = n T_N, averaged over a window ten times longer, as the channel's detector does.
// A window of `window_s` (at least `min_integrations`): with 200 ms coherent integrations at
// 12 dB-Hz (SNR 3.2) a 2 s window scatters by about 1 dB.
//
// Phase lock of data-wiped integrations: their prompt has no bit sign left, so the window's
// mean I over its mean |Q| reads the carrier phase error directly (about 0.8 with noise
// alone, 2.5 at an SNR of 2, i.e. 10 dB-Hz with 200 ms).
#include <complex>
#include <cstdint>
#include <deque>
#include <optional>

namespace deepnav::aiding {

/// One integration as the estimator sees it.
struct IntegrationPower {
  double end_s = 0.0;                 ///< when it ended (s), for the window
  double prompt_power = 0.0;          ///< sum over its coherent pieces of |P_k|^2
  double sum_t_s = 0.0;               ///< sum of the pieces' lengths
  double sum_t2_s2 = 0.0;             ///< sum of their squares (= T^2 for one coherent piece)
  double noise_power = 0.0;           ///< |N|^2 summed over the noise correlator's pieces
  double noise_s = 0.0;               ///< time the noise correlator covered
  std::complex<double> wiped_prompt;  ///< the coherent prompt when the data was wiped off (else 0)
  bool data_wiped = false;
};

/// One coherent integration of `integration_s` ending at `end_s`, its prompt and the noise
/// correlator's sum over `noise_s`.
IntegrationPower coherent_power(const std::complex<double>& prompt, const std::complex<double>& noise, double end_s,
                                double integration_s, double noise_s);

class IntegrationCn0Estimator {
 public:
  explicit IntegrationCn0Estimator(double window_s = 2.0, int min_integrations = 5)
      : window_s_(window_s), min_count_(min_integrations) {}

  void add(const IntegrationPower& p);
  void reset();
  /// At least min_integrations in the window and a noise reference.
  bool ready() const;
  /// 0 when the window holds no signal power beyond the noise (or is not ready).
  double cn0_dbhz() const;
  /// Whether the window's signal power stands `sigmas` standard deviations above what noise
  /// alone gives it: with noise only each piece's |P|^2 / n is exponential with mean and
  /// deviation T_k, so the estimate C has a deviation of n / sqrt(sum T_k^2). The lowest
  /// C/N0 detected is sigmas / sqrt(sum T_k^2): 3 sigmas over 2 s of 200 ms integrations
  /// detect 6.8 dB-Hz, over 2 s of 20 ms bits 11.8 dB-Hz, over 2 s of 10 ms integrations 13.3.
  bool signal_detected(double sigmas) const;
  /// Mean I over mean |Q| of the window's data-wiped integrations (0 with fewer than
  /// min_integrations of them).
  double wiped_phase_lock_indicator() const;

 private:
  double window_s_;
  int min_count_;
  std::deque<IntegrationPower> window_;
  std::deque<IntegrationPower> noise_window_;
  /// C and n of the window (correlator units); nullopt when not ready.
  struct Estimate {
    double c = 0.0, n = 0.0, sum_t2 = 0.0;
  };
  std::optional<Estimate> estimate() const;
};

}  // namespace deepnav::aiding
