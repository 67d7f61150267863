#pragma once
// The phase-locked rate of a steered channel: the mean carrier frequency over adjoining
// windows of its accumulated carrier phase (a delta range per window, about 100 ms each).
// The phase at an integration's end is the NCO's accumulated phase (the filter's
// corrections included) plus the phase error the prompt still shows, so the loop's lag
// cancels and the filter's own NCO corrections do not echo back into the next window.
#include <cstdint>
#include <optional>

namespace deepnav::aiding {

/// A window's mean frequency and where it refers to.
struct WindowRate {
  double doppler_hz = 0.0;
  std::int64_t mid_sample = 0;  ///< the window's middle
  double window_s = 0.0;
};

class PhaseRateWindow {
 public:
  PhaseRateWindow(double sample_rate_hz, double window_s) : fs_(sample_rate_hz), window_s_(window_s) {}
  /// An integration of `samples` ended at `end_sample` with carrier phase `phase_cycles`
  /// there: the rate of the window it closes (a window closes within half an integration of
  /// its length), if it closes one; the next window starts at its end.
  std::optional<WindowRate> add(std::int64_t end_sample, double phase_cycles, int samples);
  /// Phase no longer trusted (lock lost, a stretch not steered): the next window starts afresh.
  void reset() { start_.reset(); }

 private:
  double fs_, window_s_;
  std::optional<std::int64_t> start_;  ///< integration end where the current window began
  double start_cycles_ = 0.0;          ///< carrier phase there
};

}  // namespace deepnav::aiding
