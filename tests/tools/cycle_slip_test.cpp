// The threshold benchmark's phase-lock criterion on hand-made phase series.
#include "tools/bench/cycle_slip.hpp"

#include <gtest/gtest.h>

namespace deepnav::bench {
namespace {

using Series = std::vector<std::pair<double, double>>;

/// 10 ms integrations of a channel whose NCO phase follows the truth's (+ offset), with a
/// jump of `slip_cycles` at `slip_s`.
Series nco_following(const Series& truth, double sign, double slip_s, double slip_cycles) {
  Series out;
  for (int k = 0; k < 300; ++k) {
    const double t = k / 100.0;
    out.emplace_back(t, sign * interpolate(truth, t) + 0.2 + (t >= slip_s ? slip_cycles : 0.0));
  }
  return out;
}

Series truth_phase() {  // 100 Hz Doppler: 100 cycles a second, at 10 Hz
  Series out;
  for (int k = 0; k <= 40; ++k) out.emplace_back(0.1 * k, 100.0 * 0.1 * k);
  return out;
}

TEST(Interpolate, LinearInsideEndValuesOutside) {
  const Series s{{0.0, 1.0}, {1.0, 3.0}};
  EXPECT_DOUBLE_EQ(interpolate(s, 0.25), 1.5);
  EXPECT_DOUBLE_EQ(interpolate(s, -1.0), 1.0);
  EXPECT_DOUBLE_EQ(interpolate(s, 2.0), 3.0);
}

TEST(FirstCycleSlip, FindsAHalfCycleJumpInEitherSignConvention) {
  const Series truth = truth_phase();
  EXPECT_NEAR(first_cycle_slip_s(nco_following(truth, 1.0, 1.5, 0.5), truth), 1.5, 1e-9);
  EXPECT_NEAR(first_cycle_slip_s(nco_following(truth, -1.0, 2.0, -0.5), truth), 2.0, 1e-9);
}

TEST(FirstCycleSlip, NoSlipIsTheEndOfTracking) {
  const Series truth = truth_phase();
  EXPECT_DOUBLE_EQ(first_cycle_slip_s(nco_following(truth, 1.0, 99.0, 0.5), truth), 2.99);
  // Jitter under the 0.35-cycle limit is no slip.
  EXPECT_DOUBLE_EQ(first_cycle_slip_s(nco_following(truth, 1.0, 1.0, 0.3), truth), 2.99);
}

TEST(FirstCycleSlip, TooShortATrackToJudge) {
  const Series truth = truth_phase();
  Series short_track(nco_following(truth, 1.0, 99.0, 0.0));
  short_track.resize(30);
  EXPECT_DOUBLE_EQ(first_cycle_slip_s(short_track, truth), short_track.back().first);
  EXPECT_DOUBLE_EQ(first_cycle_slip_s({}, truth), 0.0);
}

}  // namespace
}  // namespace deepnav::bench
