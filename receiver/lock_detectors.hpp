#pragma once
// C/N0 estimate and lock indicators of a tracking channel.
//
// C/N0: the prompt power against the power of a noise correlator (an untracked PRN's
// code on the same carrier wipe-off), both averaged over a window:
// C/N0 = (E|P|^2 - E|N|^2) / (E|N|^2 T). The noise correlator sees the same noise
// density as the prompt, so the estimate needs no knowledge of the front-end scaling.
// Phase lock: the window's mean |I| against its mean |Q| (data-bit insensitive). Locked,
// |I| carries the signal amplitude and |Q| only noise; unlocked both are alike. Unlike
// the cos(2 dphi) average this stays usable near 30 dB-Hz with 1 ms integrations.
#include <complex>
#include <deque>

namespace deepnav {

class LockDetector {
 public:
  explicit LockDetector(std::size_t window = 50) : window_(window) {}
  void add(const std::complex<double>& prompt, const std::complex<double>& noise, double integration_s);
  /// Valid once the window is full.
  bool ready() const { return prompt_power_.size() >= window_; }
  double cn0_dbhz() const;
  double phase_lock_indicator() const;  ///< mean|I| / mean|Q|: about 1 unlocked, well above 1 locked
  void reset();

 private:
  std::size_t window_;
  std::deque<double> prompt_power_, noise_power_, abs_i_, abs_q_;
  double integration_s_ = 1e-3;
};

}  // namespace deepnav
