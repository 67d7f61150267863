#pragma once
// C/N0 estimate and lock indicators of a tracking channel.
//
// C/N0: the prompt power against the power of a noise correlator (an untracked PRN's
// code on the same carrier wipe-off), both averaged over a window:
// C/N0 = (E|P|^2 - E|N|^2) / (E|N|^2 T). The noise correlator sees the same noise
// density as the prompt, so the estimate needs no knowledge of the front-end scaling.
// E|P|^2 is averaged over the window, E|N|^2 / T over ten windows and across changes of
// the integration length: with 50 epochs alone the noise average has a 14 % (0.6 dB)
// scatter that would dominate the estimate's error at high C/N0. The noise sum may cover
// only part of an integration (its length T_N given): |N|^2 / T_N has the same mean and,
// an exponential variable whatever T_N, the same relative scatter.
// Phase lock: the window's mean |I| against its mean |Q| (data-bit insensitive). Locked,
// |I| carries the signal amplitude and |Q| only noise; unlocked both are alike. Unlike
// the cos(2 dphi) average (also reported) this stays usable near 30 dB-Hz with 1 ms
// integrations. Both lock flags have hysteresis: a flag rises after `confirm_epochs`
// consecutive epochs above its "on" threshold and falls after as many below its "off"
// threshold.
#include <complex>

#include "receiver/tracking/windowed_sum.hpp"

namespace deepnav {

struct LockThresholds {
  double pll_on = 1.5;          ///< mean|I| / mean|Q| to declare phase lock
  double pll_off = 1.25;        ///< ... and to lose it
  double code_on_dbhz = 26.0;   ///< C/N0 to declare code lock
  double code_off_dbhz = 23.0;  ///< ... and to lose it
  int confirm_epochs = 5;
  /// Averaging window: this long, but at least 20 epochs. With 1 ms epochs a 200-epoch
  /// window keeps pure noise below about 20 dB-Hz (a 50-epoch one reads up to 25 dB-Hz).
  double window_s = 0.2;
};

class LockDetector {
 public:
  explicit LockDetector(LockThresholds thresholds = {});
  /// One integration: its prompt over integration_s, and the noise correlator over noise_s
  /// (a part of it, or all of it when negative; 0: no noise sum this time).
  void add(const std::complex<double>& prompt, const std::complex<double>& noise, double integration_s,
           double noise_s = -1.0);
  /// Valid once the window is full.
  bool ready() const { return prompt_power_.size() >= window_; }
  double cn0_dbhz() const;
  double phase_lock_indicator() const;  ///< mean|I| / mean|Q|: about 1 unlocked, well above 1 locked
  /// (sum I^2 - sum Q^2) / (sum I^2 + sum Q^2) = mean cos(2 dphi) at high C/N0; 0 unlocked.
  double cos_two_phi() const;
  bool pll_locked() const { return pll_lock_; }
  bool code_locked() const { return code_lock_; }
  void reset();

 private:
  void update_flags();

  LockThresholds th_;
  std::size_t window_ = 200;  ///< epochs, from window_s and the current integration length
  WindowedSum prompt_power_, abs_i_, abs_q_, i2_, q2_;
  WindowedSum noise_power_;  ///< |N|^2 / T: comparable across integration lengths
  double integration_s_ = 1e-3;
  bool pll_lock_ = false, code_lock_ = false;
  int pll_count_ = 0, code_count_ = 0;  ///< consecutive epochs pointing at the other state
};

}  // namespace deepnav
