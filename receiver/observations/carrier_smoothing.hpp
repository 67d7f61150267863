#pragma once
// Carrier smoothing of code pseudoranges (Hatch filter), per satellite:
//
//   P_s(k) = P(k) / n + (n - 1) / n * (P_s(k-1) + lambda (phi(k) - phi(k-1))),  n = min(k, N)
//
// with phi the carrier phase in cycles, RINEX sign (it grows with the range), and N the
// window in epochs. The carrier follows the range change with millimetre noise, so the
// code's noise and its fast multipath average down over the window; what changes slowly
// (ionosphere divergence: code delay and phase advance drift apart at twice the
// ionosphere's rate, centimetres over 100 s) stays.
//
// The filter restarts (n = 1, the raw pseudorange) when the phase cannot be trusted to
// connect two epochs: a loss-of-lock indication, no phase or no pseudorange at this epoch,
// the satellite absent at the previous epoch (more than 1.5 intervals since its previous
// phase), a receiver clock re-set (the code steps by c x 1 ms while the phase may or may
// not), or a cycle slip seen as a disagreement between the code and phase changes beyond
// `slip_threshold_m` (the code's noise between two epochs is metres at most).
#include <map>
#include <optional>

namespace deepnav {

struct CarrierSmoothingConfig {
  double window_s = 100.0;        ///< N x the epoch interval
  double slip_threshold_m = 30.0; ///< |delta code - lambda delta phase| beyond this: a slip
};

class CarrierSmoother {
 public:
  CarrierSmoother(CarrierSmoothingConfig config, double interval_s, double wavelength_m);

  /// What one satellite's filter did at an epoch.
  enum class Step { raw, smoothed, restarted };
  struct Result {
    double pseudorange_m = 0.0;
    Step step = Step::raw;
    int epochs = 1;               ///< n: epochs averaged (1 after a restart)
  };
  /// The smoothed pseudorange of `prn` at time t_s. `loss_of_lock`: the receiver's LLI;
  /// `clock_reset`: the receiver clock was re-set since the previous epoch.
  Result add(int prn, double t_s, double pseudorange_m, std::optional<double> phase_cycles, bool loss_of_lock,
             bool clock_reset);

  int restarts() const { return restarts_; }
  int slips() const { return slips_; }

 private:
  struct State {
    double t_s = 0.0;
    double smoothed_m = 0.0;
    double phase_cycles = 0.0;
    double previous_code_m = 0.0;
    int n = 0;
  };
  CarrierSmoothingConfig cfg_;
  int window_epochs_;
  double wavelength_m_;
  double interval_s_;
  std::map<int, State> states_;
  int restarts_ = 0, slips_ = 0;
};

}  // namespace deepnav
