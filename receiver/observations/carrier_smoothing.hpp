#pragma once
// Carrier smoothing of code pseudoranges (Hatch filter), per satellite:
//
//   P_s(k) = P(k) / n + (n - 1) / n * (P_s(k-1) + dR(k)),  n = min(k, N)
//
// with dR(k) the range change since the previous epoch from the carrier, lambda (phi(k) -
// phi(k-1)) (phi in cycles, RINEX sign: it grows with the range), and N the window in
// epochs. The carrier follows the range with millimetre noise, so the code's noise and its
// fast multipath average down over the window; what changes slowly (ionosphere divergence:
// code delay and phase advance drift apart at twice the ionosphere's rate, centimetres over
// 100 s) stays.
//
// Where the phase cannot connect two epochs (a loss-of-lock indication, no phase at one of
// them, a receiver clock re-set, after which the phase may or may not have stepped with the
// code) the range change comes from the Dopplers instead, -lambda (D(k-1) + D(k)) / 2 dt
// (plus the clock step on a re-set): a few centimetres of error per epoch against the
// metres of restarting from the raw code, which on a handheld whose satellites report
// slips every few seconds is the difference between smoothing and none. The filter
// restarts (n = 1, the raw pseudorange) when neither connects the epochs: the satellite
// absent at the previous epoch (more than 1.5 intervals since), no Doppler where the phase
// fails, the Dopplers carrying it for longer than `max_doppler_bridge_s`, or a code change
// that disagrees with the carried range change by more than `slip_threshold_m` (a slip the
// receiver did not flag, or a code glitch).
#include <map>
#include <optional>

namespace deepnav {

struct CarrierSmoothingConfig {
  double window_s = 100.0;         ///< N x the epoch interval
  double slip_threshold_m = 30.0;  ///< |code change - carried range change| beyond this: restart
  /// Longest run of consecutive epochs carried by the Dopplers (s; 0: never): a Doppler
  /// that tracks a weak or reflected signal can be off by decimetres per second, which a
  /// long bridge integrates into metres.
  double max_doppler_bridge_s = 1.0;
};

class CarrierSmoother {
 public:
  CarrierSmoother(CarrierSmoothingConfig config, double interval_s, double wavelength_m);

  /// How one satellite's filter went from its previous epoch to this one.
  enum class Step { first, carrier, doppler, restarted };
  struct Result {
    double pseudorange_m = 0.0;
    Step step = Step::first;
    int epochs = 1;  ///< n: epochs averaged (1 after a restart)
  };
  /// The smoothed pseudorange of `prn` at time t_s. `loss_of_lock`: the receiver's LLI;
  /// `clock_jump_m`: the receiver clock's re-set since the previous epoch (0: none), by
  /// which the code stepped. Doppler: positive when the satellite approaches.
  Result add(int prn, double t_s, double pseudorange_m, std::optional<double> phase_cycles,
             std::optional<double> doppler_hz, bool loss_of_lock, double clock_jump_m);

  int restarts() const { return restarts_; }
  int slips() const { return slips_; }  ///< restarts for a code-carried disagreement
  int doppler_steps() const { return doppler_steps_; }

 private:
  struct State {
    double t_s = 0.0;
    double smoothed_m = 0.0;
    double code_m = 0.0;
    std::optional<double> phase_cycles, doppler_hz;
    int n = 0;
    double bridged_s = 0.0;  ///< since the last epoch the carrier connected
  };
  CarrierSmoothingConfig cfg_;
  int window_epochs_ = 1;
  double wavelength_m_;
  double interval_s_;
  std::map<int, State> states_;
  int restarts_ = 0, slips_ = 0, doppler_steps_ = 0;
};

}  // namespace deepnav
