#pragma once
// Bump-jumping against false lock on a BOC(1,1) side peak.
//
// The BOC(1,1) autocorrelation R(t) = 1 - 3|t| (|t| <= 1/2), |t| - 1 (1/2 <= |t| <= 1) has
// negative side peaks of magnitude 1/2 at +-1/2 chip, where a DLL is as stable as on the main
// peak. With very-early/very-late taps at +-1/2 chip, a replica on the main peak sees
// |VE| = |VL| = |P| / 2; one on a side peak sees the main peak (twice its prompt) in one of
// them. An up/down counter per side (up when that tap beats both the prompt and the other
// side, down otherwise) filters noise; reaching the threshold moves the replica half a chip
// that way. Each jump moves the prompt between a negative side peak and the positive main peak,
// so the carrier phase reference flips too: the caller turns it half a cycle.
#include <complex>

namespace deepnav {

class SidePeakGuard {
 public:
  /// threshold: net counts (integrations) before a jump; max_jumps: jumps allowed before the
  /// guard gives up (the replica keeps bouncing: no stable main peak, the channel is lost).
  /// Throws std::invalid_argument for a threshold below 1 or negative max_jumps.
  explicit SidePeakGuard(int threshold = 20, int max_jumps = 2);
  /// One integration's very-early, prompt and very-late sums. Returns the jump to apply to the
  /// replica's code phase (+0.5: advance, toward the very-early tap; -0.5; 0: none).
  double add(const std::complex<double>& very_early, const std::complex<double>& prompt,
             const std::complex<double>& very_late);
  int jumps() const { return jumps_; }
  /// More jumps than allowed: the channel should declare itself lost.
  bool exhausted() const { return jumps_ > max_jumps_; }

 private:
  int threshold_, max_jumps_;
  int early_count_ = 0, late_count_ = 0, jumps_ = 0;
};

}  // namespace deepnav
