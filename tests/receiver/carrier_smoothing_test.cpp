#include "receiver/observations/carrier_smoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace deepnav {
namespace {

constexpr double kLambda = 0.19029367279836487;  // GPS L1 wavelength (m)
constexpr double kInterval = 0.25;

/// A satellite receding at 300 m/s: range, carrier phase (RINEX sign: grows with the
/// range, plus an arbitrary ambiguity) and Doppler (positive when approaching).
struct Sat {
  double range(double t) const { return 2.2e7 + 300.0 * t; }
  double phase(double t) const { return range(t) / kLambda + 12345.0; }
  double doppler() const { return -300.0 / kLambda; }
};

TEST(CarrierSmoothing, AveragesCodeNoiseDownOverTheWindow) {
  CarrierSmoother s({}, kInterval, kLambda);  // 100 s: 400 epochs
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  Sat sat;
  double sum2_raw = 0.0, sum2_smoothed = 0.0;
  int n = 0;
  for (int k = 0; k < 800; ++k) {
    const double t = k * kInterval;
    const double code = sat.range(t) + noise(rng);
    const CarrierSmoother::Result r = s.add(7, t, code, sat.phase(t), sat.doppler(), false, 0.0);
    EXPECT_EQ(r.step, k == 0 ? CarrierSmoother::Step::first : CarrierSmoother::Step::carrier);
    EXPECT_EQ(r.epochs, std::min(k + 1, 400));
    if (k >= 400) {
      sum2_raw += std::pow(code - sat.range(t), 2);
      sum2_smoothed += std::pow(r.pseudorange_m - sat.range(t), 2);
      ++n;
    }
  }
  const double raw = std::sqrt(sum2_raw / n), smoothed = std::sqrt(sum2_smoothed / n);
  EXPECT_NEAR(raw, 1.0, 0.1);
  // A recursive average over N = 400 epochs: about 1 / sqrt(2N - 1) of the code noise.
  EXPECT_LT(smoothed, 0.06);
  EXPECT_EQ(s.restarts(), 0);
}

TEST(CarrierSmoothing, LossOfLockIsCarriedByTheDopplersForAtMostTheBridge) {
  CarrierSmoothingConfig c;
  c.max_doppler_bridge_s = 0.5;  // two epochs
  CarrierSmoother s(c, kInterval, kLambda);
  Sat sat;
  for (int k = 0; k < 20; ++k)
    s.add(3, k * kInterval, sat.range(k * kInterval) + 2.0, sat.phase(k * kInterval), sat.doppler(), false, 0.0);
  // A slip of 1000 cycles with the loss-of-lock indicator set, then two more flagged epochs:
  // the first two are carried by the Dopplers (the code offset of 2 m stays smoothed), the
  // third is beyond the bridge and restarts from the raw code.
  double t = 20 * kInterval;
  CarrierSmoother::Result r = s.add(3, t, sat.range(t) + 2.0, sat.phase(t) + 1000.0, sat.doppler(), true, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::doppler);
  EXPECT_EQ(r.epochs, 21);
  EXPECT_NEAR(r.pseudorange_m, sat.range(t) + 2.0, 1e-6);
  t += kInterval;
  r = s.add(3, t, sat.range(t) + 2.0, sat.phase(t) + 1000.0, sat.doppler(), true, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::doppler);
  t += kInterval;
  r = s.add(3, t, sat.range(t) + 2.0, sat.phase(t) + 1000.0, sat.doppler(), true, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::restarted);
  EXPECT_EQ(r.epochs, 1);
  EXPECT_EQ(s.doppler_steps(), 2);
  EXPECT_EQ(s.restarts(), 1);
  // The next epoch connects by the (new) phase again.
  t += kInterval;
  r = s.add(3, t, sat.range(t) + 2.0, sat.phase(t) + 1000.0, sat.doppler(), false, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::carrier);
  EXPECT_EQ(r.epochs, 2);
}

TEST(CarrierSmoothing, RestartsOnAnUnflaggedSlipAGapOrNoDoppler) {
  CarrierSmoother s({}, kInterval, kLambda);
  Sat sat;
  for (int k = 0; k < 8; ++k)
    s.add(5, k * kInterval, sat.range(k * kInterval), sat.phase(k * kInterval), sat.doppler(), false, 0.0);
  // A 100 m jump of the phase that the receiver did not flag: code and carrier disagree.
  double t = 8 * kInterval;
  CarrierSmoother::Result r = s.add(5, t, sat.range(t), sat.phase(t) + 100.0 / kLambda, sat.doppler(), false, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::restarted);
  EXPECT_EQ(s.slips(), 1);
  // Absent for two epochs: a gap restarts it.
  t += 3 * kInterval;
  r = s.add(5, t, sat.range(t), sat.phase(t), sat.doppler(), false, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::restarted);
  // Loss of lock without a Doppler at this epoch: nothing carries it.
  t += kInterval;
  r = s.add(5, t, sat.range(t), sat.phase(t), std::nullopt, true, 0.0);
  EXPECT_EQ(r.step, CarrierSmoother::Step::restarted);
  EXPECT_EQ(s.restarts(), 3);
  // No phase at all (a code-only satellite): the raw code each epoch.
  CarrierSmoother code_only({}, kInterval, kLambda);
  for (int k = 0; k < 4; ++k) {
    r = code_only.add(9, k * kInterval, sat.range(k * kInterval) + 1.0, std::nullopt, std::nullopt, false, 0.0);
    EXPECT_EQ(r.epochs, 1);
    EXPECT_DOUBLE_EQ(r.pseudorange_m, sat.range(k * kInterval) + 1.0);
  }
}

TEST(CarrierSmoothing, FollowsAReceiverClockReset) {
  CarrierSmoother s({}, kInterval, kLambda);
  Sat sat;
  const double jump_m = 299792.458;  // 1 ms
  for (int k = 0; k < 8; ++k)
    s.add(2, k * kInterval, sat.range(k * kInterval), sat.phase(k * kInterval), sat.doppler(), false, 0.0);
  // The code steps by c x 1 ms, the phase does not: carried by the Dopplers plus the step.
  const double t = 8 * kInterval;
  const CarrierSmoother::Result r = s.add(2, t, sat.range(t) + jump_m, sat.phase(t), sat.doppler(), false, jump_m);
  EXPECT_EQ(r.step, CarrierSmoother::Step::doppler);
  EXPECT_NEAR(r.pseudorange_m, sat.range(t) + jump_m, 1e-6);
  EXPECT_EQ(s.restarts(), 0);
}

TEST(CarrierSmoothing, RejectsAnImpossibleConfiguration) {
  EXPECT_THROW(CarrierSmoother({}, 0.0, kLambda), std::invalid_argument);
  EXPECT_THROW(CarrierSmoother({}, kInterval, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
