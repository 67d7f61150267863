#include "receiver/observations/carrier_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepnav {

CarrierSmoother::CarrierSmoother(CarrierSmoothingConfig config, double interval_s, double wavelength_m)
    : cfg_(config), wavelength_m_(wavelength_m), interval_s_(interval_s) {
  if (!(interval_s > 0.0) || !(wavelength_m > 0.0) || !(cfg_.window_s >= 0.0))
    throw std::invalid_argument("carrier smoothing needs a positive epoch interval, wavelength and window");
  window_epochs_ = std::max(1, static_cast<int>(std::lround(cfg_.window_s / interval_s)));
}

CarrierSmoother::Result CarrierSmoother::add(int prn, double t_s, double pseudorange_m,
                                             std::optional<double> phase_cycles, bool loss_of_lock, bool clock_reset) {
  Result r;
  r.pseudorange_m = pseudorange_m;
  const auto it = states_.find(prn);
  if (!phase_cycles) {
    // Without a phase there is nothing to carry the next epoch across: start again there.
    if (it != states_.end()) {
      states_.erase(it);
      ++restarts_;
    }
    return r;
  }
  const bool had = it != states_.end();
  bool connected = had && !loss_of_lock && !clock_reset && t_s - it->second.t_s <= 1.5 * interval_s_ &&
                   t_s > it->second.t_s;
  if (connected) {
    const State& s = it->second;
    const double carrier_change_m = wavelength_m_ * (*phase_cycles - s.phase_cycles);
    if (std::abs((pseudorange_m - s.previous_code_m) - carrier_change_m) > cfg_.slip_threshold_m) {
      connected = false;
      ++slips_;
    }
  }
  State& s = states_[prn];
  if (connected) {
    s.n = std::min(s.n + 1, window_epochs_);
    const double carried = s.smoothed_m + wavelength_m_ * (*phase_cycles - s.phase_cycles);
    s.smoothed_m = pseudorange_m / s.n + (s.n - 1.0) / s.n * carried;
    r.step = Step::smoothed;
  } else {
    if (had) ++restarts_;
    s.n = 1;
    s.smoothed_m = pseudorange_m;
    r.step = had ? Step::restarted : Step::raw;
  }
  s.t_s = t_s;
  s.phase_cycles = *phase_cycles;
  s.previous_code_m = pseudorange_m;
  r.pseudorange_m = s.smoothed_m;
  r.epochs = s.n;
  return r;
}

}  // namespace deepnav
