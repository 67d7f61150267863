#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "signals/galileo/e1_modulation.hpp"

namespace deepnav::galileo {
namespace {

/// Autocorrelation of one chip's waveform, integral over t of p(t) p(t + tau) (p = 0 outside
/// [0, 1)), by the midpoint rule on a grid fine enough to be exact for square waves whose
/// edges fall on multiples of 1/12 chip when tau does.
double pulse_correlation(E1Subcarrier a, E1Subcarrier b, double tau) {
  constexpr int kSteps = 12 * 400;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double t = (i + 0.5) / kSteps;
    if (t + tau < 0.0 || t + tau >= 1.0) continue;
    sum += e1_subcarrier(a, t) * e1_subcarrier(b, t + tau);
  }
  return sum / kSteps;
}

/// Circular correlation of two sample sequences at a lag, divided by their length.
double circular_correlation(const std::vector<float>& a, const std::vector<float>& b, std::size_t lag) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += double{a[i]} * b[(i + lag) % b.size()];
  return sum / static_cast<double>(a.size());
}

TEST(GalileoE1Modulation, SubcarriersAreSquareWavesStartingHigh) {
  EXPECT_EQ(boc_subcarrier(1, 0.0), 1.0);
  EXPECT_EQ(boc_subcarrier(1, 0.49), 1.0);
  EXPECT_EQ(boc_subcarrier(1, 0.5), -1.0);
  EXPECT_EQ(boc_subcarrier(1, 0.99), -1.0);
  EXPECT_EQ(boc_subcarrier(1, 3.25), 1.0);    // any chip: only the fraction counts
  EXPECT_EQ(boc_subcarrier(1, -0.25), -1.0);  // = 0.75 of the chip before
  // BOC(6,1): twelve half cycles per chip.
  for (int half = 0; half < 12; ++half) {
    EXPECT_EQ(boc_subcarrier(6, (half + 0.5) / 12.0), half % 2 == 0 ? 1.0 : -1.0) << "half " << half;
  }
  EXPECT_THROW(boc_subcarrier(0, 0.1), std::invalid_argument);
}

TEST(GalileoE1Modulation, CbocLevelsAndPower) {
  EXPECT_NEAR(kCbocAlpha * kCbocAlpha + kCbocBeta * kCbocBeta, 1.0, 1e-15);
  EXPECT_NEAR(kCbocBeta * kCbocBeta / (kCbocAlpha * kCbocAlpha), 0.1, 1e-15);  // 1/11 of the power on BOC(6,1)
  // In the first twelfth of a chip both subcarriers are +1; in the second sc_b is -1.
  EXPECT_NEAR(e1_subcarrier(E1Subcarrier::kCbocE1b, 0.04), kCbocAlpha + kCbocBeta, 1e-15);
  EXPECT_NEAR(e1_subcarrier(E1Subcarrier::kCbocE1b, 0.12), kCbocAlpha - kCbocBeta, 1e-15);
  EXPECT_NEAR(e1_subcarrier(E1Subcarrier::kCbocE1c, 0.04), kCbocAlpha - kCbocBeta, 1e-15);
  EXPECT_NEAR(e1_subcarrier(E1Subcarrier::kCbocE1c, 0.12), kCbocAlpha + kCbocBeta, 1e-15);
  EXPECT_NEAR(e1_subcarrier(E1Subcarrier::kCbocE1b, 0.54), -kCbocAlpha + kCbocBeta, 1e-15);
}

TEST(GalileoE1Modulation, CompositeSignalTakesTheIcdLevels) {
  // (e_B - e_C)/sqrt2 alpha sc_a + (e_B + e_C)/sqrt2 beta sc_b: with equal levels only the
  // BOC(6,1) part remains, with opposite ones only the BOC(1,1) part.
  const double t = 0.12;  // sc_a = +1, sc_b = -1
  EXPECT_NEAR(e1_composite(1, 1, t), -std::sqrt(2.0) * kCbocBeta, 1e-15);
  EXPECT_NEAR(e1_composite(-1, -1, t), std::sqrt(2.0) * kCbocBeta, 1e-15);
  EXPECT_NEAR(e1_composite(1, -1, t), std::sqrt(2.0) * kCbocAlpha, 1e-15);
  EXPECT_NEAR(e1_composite(-1, 1, t), -std::sqrt(2.0) * kCbocAlpha, 1e-15);
}

TEST(GalileoE1Modulation, Boc11AutocorrelationHasItsSidePeaksAtHalfAChip) {
  // BOC(1,1) (sine phased): R(tau) = 1 - 3|tau| up to half a chip, |tau| - 1 beyond.
  for (double tau : {0.0, 1.0 / 6.0, 1.0 / 3.0, 0.5, 2.0 / 3.0, 0.75, 1.0}) {
    const double expected = tau <= 0.5 ? 1.0 - 3.0 * tau : tau - 1.0;
    EXPECT_NEAR(pulse_correlation(E1Subcarrier::kBoc11, E1Subcarrier::kBoc11, tau), expected, 1e-12) << tau;
    EXPECT_NEAR(pulse_correlation(E1Subcarrier::kBoc11, E1Subcarrier::kBoc11, -tau), expected, 1e-12) << -tau;
  }
}

TEST(GalileoE1Modulation, CbocAutocorrelationPeaks) {
  for (E1Subcarrier kind : {E1Subcarrier::kCbocE1b, E1Subcarrier::kCbocE1c}) {
    EXPECT_NEAR(pulse_correlation(kind, kind, 0.0), 1.0, 1e-12);
    // At half a chip sc_a meets its inverse (-alpha^2 / 2) and sc_b itself three cycles on
    // (+beta^2 / 2); the cross terms cancel: -9/22.
    EXPECT_NEAR(pulse_correlation(kind, kind, 0.5), -9.0 / 22.0, 1e-12);
    EXPECT_NEAR(pulse_correlation(kind, kind, -0.5), -9.0 / 22.0, 1e-12);
  }
  // E1-B against E1-C (the receiver's BOC(1,1)-like view of the pair): alpha^2 - beta^2.
  EXPECT_NEAR(pulse_correlation(E1Subcarrier::kCbocE1b, E1Subcarrier::kCbocE1c, 0.0), 9.0 / 11.0, 1e-12);
  // A BOC(1,1) replica against the transmitted E1-B keeps alpha of its power (sc_b averages out).
  EXPECT_NEAR(pulse_correlation(E1Subcarrier::kBoc11, E1Subcarrier::kCbocE1b, 0.0), kCbocAlpha, 1e-12);
}

TEST(GalileoE1Modulation, ReplicaOfARealCodeCorrelatesAsTheWaveform) {
  // 12 samples a chip: half a chip is 6 samples. The code's own sidelobes (below 0.054 of
  // the peak) blur the waveform's values by at most that fraction.
  constexpr std::size_t kPerChip = 12;
  constexpr double kMidSample = 0.5 / kPerChip;  // samples in mid-twelfth, never on a subcarrier edge
  const E1CodeChips& code = e1b_code_chips(11);
  for (E1Subcarrier kind : {E1Subcarrier::kBoc11, E1Subcarrier::kCbocE1b}) {
    const auto replica = e1_replica(code, kind, kMidSample, 1.0 / kPerChip, kE1CodeLength_chips * kPerChip);
    const double side_expected = kind == E1Subcarrier::kBoc11 ? -0.5 : -9.0 / 22.0;
    EXPECT_NEAR(circular_correlation(replica, replica, 0), 1.0, 1e-6);
    EXPECT_NEAR(circular_correlation(replica, replica, kPerChip / 2), side_expected, 0.03);
    EXPECT_NEAR(circular_correlation(replica, replica, replica.size() - kPerChip / 2), side_expected, 0.03);
  }
  // BOC(1,1)'s side peaks are its most negative values within a chip of the main peak.
  const auto boc = e1_replica(code, E1Subcarrier::kBoc11, kMidSample, 1.0 / kPerChip, kE1CodeLength_chips * kPerChip);
  std::size_t lowest_lag = 1;
  for (std::size_t lag = 2; lag < kPerChip; ++lag) {
    if (circular_correlation(boc, boc, lag) < circular_correlation(boc, boc, lowest_lag)) lowest_lag = lag;
  }
  EXPECT_EQ(lowest_lag, kPerChip / 2);
}

TEST(GalileoE1Modulation, ReplicaFollowsTheCodeAcrossItsEnd) {
  const E1CodeChips& code = e1c_code_chips(3);
  // Two samples a chip from the last chip: chip 4091 twice, then chips 0 and 1 of the next period.
  const auto r = e1_replica(code, E1Subcarrier::kBoc11, kE1CodeLength_chips - 1.0, 0.5, 6);
  EXPECT_EQ(r[0], code[4091]);
  EXPECT_EQ(r[1], -code[4091]);
  EXPECT_EQ(r[2], code[0]);
  EXPECT_EQ(r[3], -code[0]);
  EXPECT_EQ(r[4], code[1]);
  // A negative start phase is the previous period's end.
  EXPECT_EQ(e1_replica(code, E1Subcarrier::kBoc11, -0.75, 1.0, 1)[0], code[4091]);
}

}  // namespace
}  // namespace deepnav::galileo
