#include "signals/sim/receiver_clock_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace deepnav {
namespace {

TEST(ReceiverClockModel, NoiseFreeClockIsDeterministicLine) {
  ReceiverClockModel clock(1e-3, 2e-7, 0.0, 0.0, 1);
  for (int k = 0; k < 1000; ++k) clock.step(1e-3);
  EXPECT_NEAR(clock.state().bias_s, 1e-3 + 2e-7 * 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(clock.state().drift_sps, 2e-7);
}

TEST(ReceiverClockModel, DriftRandomWalkVarianceMatchesSpectralDensity) {
  // Random-walk frequency noise: var(drift(T)) = S_d T with S_d = 2 pi^2 h_-2.
  const double h_m2 = 2e-20, T = 10.0;
  const int runs = 400;
  double sum2 = 0.0;
  for (int r = 0; r < runs; ++r) {
    ReceiverClockModel clock(0.0, 0.0, 0.0, h_m2, 1000 + r);
    for (int k = 0; k < 100; ++k) clock.step(T / 100);
    sum2 += clock.state().drift_sps * clock.state().drift_sps;
  }
  const double expected = 2.0 * M_PI * M_PI * h_m2 * T;
  EXPECT_NEAR(sum2 / runs / expected, 1.0, 0.2);
}

TEST(ReceiverClockModel, WhiteFrequencyNoiseGivesBiasRandomWalk) {
  // White frequency noise: var(bias(T)) = S_b T with S_b = h0 / 2, independent of the step size.
  const double h0 = 2e-19, T = 5.0;
  const int runs = 400;
  double sum2 = 0.0;
  for (int r = 0; r < runs; ++r) {
    ReceiverClockModel clock(0.0, 0.0, h0, 0.0, 77 + r);
    for (int k = 0; k < 50; ++k) clock.step(T / 50);
    sum2 += clock.state().bias_s * clock.state().bias_s;
  }
  EXPECT_NEAR(sum2 / runs / (h0 / 2 * T), 1.0, 0.2);
}

}  // namespace
}  // namespace deepnav
