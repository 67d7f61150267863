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
                                             std::optional<double> phase_cycles, std::optional<double> doppler_hz,
                                             bool loss_of_lock, double clock_jump_m) {
  const auto it = states_.find(prn);
  const bool had = it != states_.end();
  std::optional<double> change_m;  // range change since the previous epoch, carried
  Step how = Step::restarted;
  if (had) {
    const State& s = it->second;
    const double dt = t_s - s.t_s;
    if (dt > 0.0 && dt <= 1.5 * interval_s_) {
      if (phase_cycles && s.phase_cycles && !loss_of_lock && clock_jump_m == 0.0) {
        change_m = wavelength_m_ * (*phase_cycles - *s.phase_cycles);
        how = Step::carrier;
      } else if (doppler_hz && s.doppler_hz && s.bridged_s + dt <= cfg_.max_doppler_bridge_s + 1e-9) {
        change_m = -wavelength_m_ * 0.5 * (*doppler_hz + *s.doppler_hz) * dt + clock_jump_m;
        how = Step::doppler;
      }
    }
    if (change_m && std::abs(pseudorange_m - s.code_m - *change_m) > cfg_.slip_threshold_m) {
      change_m.reset();
      how = Step::restarted;
      ++slips_;
    }
  }
  const double bridged_before = had ? it->second.bridged_s : 0.0;
  const double dt = had ? t_s - it->second.t_s : 0.0;
  State& s = states_[prn];
  Result r;
  s.bridged_s = how == Step::doppler ? bridged_before + dt : 0.0;
  if (change_m) {
    s.n = std::min(s.n + 1, window_epochs_);
    s.smoothed_m = pseudorange_m / s.n + (s.n - 1.0) / s.n * (s.smoothed_m + *change_m);
    if (how == Step::doppler) ++doppler_steps_;
  } else {
    if (had) ++restarts_;
    s.n = 1;
    s.smoothed_m = pseudorange_m;
    how = had ? Step::restarted : Step::first;
  }
  s.t_s = t_s;
  s.code_m = pseudorange_m;
  s.phase_cycles = phase_cycles;
  s.doppler_hz = doppler_hz;
  r.pseudorange_m = s.smoothed_m;
  r.step = how;
  r.epochs = s.n;
  return r;
}

}  // namespace deepnav
