#include "receiver/tracking/tracking_loops.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>

#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double kT = 1e-3;

/// Closes a noise-free carrier loop around `filter`: the NCO phase integrates the filter's
/// frequency and the discriminator sees the true minus the NCO phase at each epoch end.
/// Returns the phase error (cycles) after `seconds`.
double run_carrier_loop(CarrierLoopFilter& filter, const std::function<double(double)>& true_phase_cycles,
                        double seconds, bool fll) {
  double nco_phase = 0.0, freq = filter.frequency_hz(), error = 0.0;
  const int steps = static_cast<int>(seconds / kT);
  for (int k = 1; k <= steps; ++k) {
    const double t = k * kT;
    nco_phase += freq * kT;
    error = true_phase_cycles(t) - nco_phase;
    // The frequency error a discriminator would see over this epoch: mean true frequency minus the NCO's.
    const double f_err = (true_phase_cycles(t) - true_phase_cycles(t - kT)) / kT - freq;
    freq = filter.update(2.0 * M_PI * error, fll ? 2.0 * M_PI * f_err : 0.0, kT);
  }
  return error;
}

TEST(TrackingLoops, Discriminators) {
  EXPECT_NEAR(costas_phase_error_cycles(std::polar(1.0, 0.2)), 0.2 / (2 * M_PI), 1e-12);
  EXPECT_NEAR(costas_phase_error_cycles(-std::polar(1.0, 0.2)), 0.2 / (2 * M_PI), 1e-12);  // data bit flip
  EXPECT_NEAR(fll_frequency_error_hz(std::polar(1.0, 0.0), std::polar(1.0, 2 * M_PI * 0.05), 1e-3), 50.0, 1e-9);
  EXPECT_NEAR(fll_frequency_error_hz(std::polar(1.0, 0.0), -std::polar(1.0, 2 * M_PI * 0.05), 1e-3), 50.0, 1e-9);
  EXPECT_NEAR(dll_code_error_chips(1.0, 1.0, 0.5), 0.0, 1e-12);
  // Triangle with the replica lagging by 0.1 chip, spacing 0.5: E = 1 - 0.15, L = 1 - 0.35.
  EXPECT_NEAR(dll_code_error_chips(0.85, 0.65, 0.5), 0.1, 1e-12);
  EXPECT_NEAR(dll_code_error_chips(0.65, 0.85, 0.5), -0.1, 1e-12);
}

TEST(TrackingLoops, SecondOrderPllFollowsAFrequencyStepWithoutPhaseError) {
  CarrierLoopFilter f(2, 15.0, 0.0, 0.0);
  const double e = run_carrier_loop(
      f, [](double t) { return 5.0 * t + 0.1; }, 2.0, false);
  EXPECT_NEAR(e, 0.0, 1e-5);
  EXPECT_NEAR(f.frequency_hz(), 5.0, 1e-3);
}

TEST(TrackingLoops, SecondOrderPllLagsADopplerRateByTwoPiROverOmegaSquared) {
  const double bn = 15.0, rate = 10.0;
  CarrierLoopFilter f(2, bn, 0.0, 0.0);
  const double e = run_carrier_loop(
      f, [&](double t) { return 0.5 * rate * t * t; }, 2.0, false);
  const double w0 = bn / 0.53;
  const double expected_rad = 2.0 * M_PI * rate / (w0 * w0);
  EXPECT_NEAR(2.0 * M_PI * e, expected_rad, 0.05 * expected_rad);
}

TEST(TrackingLoops, ThirdOrderPllFollowsADopplerRateWithoutPhaseError) {
  CarrierLoopFilter f(3, 18.0, 0.0, 0.0);
  const double e = run_carrier_loop(
      f, [](double t) { return 20.0 * t + 0.5 * 10.0 * t * t; }, 3.0, false);
  EXPECT_NEAR(e, 0.0, 1e-5);
  EXPECT_NEAR(f.frequency_hz(), 20.0 + 10.0 * 3.0, 1e-2);
}

TEST(TrackingLoops, FllAloneConvergesOnAFrequencyOffset) {
  // PLL bandwidth 0: only the frequency-locked loop acts; 1st order, time constant 1/w0f.
  CarrierLoopFilter f(2, 0.0, 10.0, 0.0);
  run_carrier_loop(
      f, [](double t) { return 150.0 * t; }, 0.5, true);
  EXPECT_NEAR(f.frequency_hz(), 150.0, 0.01);
  CarrierLoopFilter f3(3, 0.0, 10.0, 0.0);  // 2nd-order FLL assist of the 3rd-order PLL
  run_carrier_loop(
      f3, [](double t) { return 150.0 * t + 0.5 * 5.0 * t * t; }, 2.0, true);
  EXPECT_NEAR(f3.frequency_hz(), 150.0 + 5.0 * 2.0, 0.05);
}

TEST(TrackingLoops, CarrierAidedDllRemovesACodeOffsetWithTimeConstantOneOverFourBn) {
  const double bn = 1.0, doppler = 1500.0;
  double replica = 0.0;
  const double truth = 0.3;        // chips ahead of the replica, moving with the carrier-aided rate
  for (int k = 0; k < 250; ++k) {  // 0.25 s = one time constant
    const double error = truth - replica;
    const double rate = carrier_aided_code_rate_cps(doppler, error, bn);
    replica += (rate - gps::kCodeRate_cps * (1.0 + doppler / gps::kL1_Hz)) * kT;
  }
  EXPECT_NEAR(truth - replica, 0.3 * std::exp(-1.0), 0.003);
  EXPECT_NEAR(carrier_aided_code_rate_cps(doppler, 0.0, bn), 1.023e6 + 1500.0 / 1540.0, 1e-6);
}

TEST(TrackingLoops, BadSettingsAreRejected) {
  EXPECT_THROW(CarrierLoopFilter(4, 15.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(CarrierLoopFilter(2, -1.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(ScalarLoopController(0.0, 1, LoopBandwidths{}), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
