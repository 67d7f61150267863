#include "aiding/phase_rate_window.hpp"

#include <cmath>

namespace deepnav::aiding {

std::optional<WindowRate> PhaseRateWindow::add(std::int64_t end_sample, double phase_cycles, int samples) {
  const auto window = static_cast<std::int64_t>(std::llround(window_s_ * fs_));
  std::optional<WindowRate> rate;
  if (start_ && end_sample - *start_ >= window - samples / 2) {
    WindowRate r;
    r.window_s = static_cast<double>(end_sample - *start_) / fs_;
    r.doppler_hz = (phase_cycles - start_cycles_) / r.window_s;
    r.mid_sample = (*start_ + end_sample) / 2;
    rate = r;
  }
  if (!start_ || rate) {
    start_ = end_sample;
    start_cycles_ = phase_cycles;
  }
  return rate;
}

}  // namespace deepnav::aiding
