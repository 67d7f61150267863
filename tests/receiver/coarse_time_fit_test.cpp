#include "receiver/pvt/coarse_time_fit.hpp"

#include <gtest/gtest.h>

#include "snapshot_scene.hpp"

namespace deepnav {
namespace {

using namespace snapshot_test;

CoarseTimeContext context_at(const GpsTime& t_hint) {
  CoarseTimeContext context;
  context.t_hint = t_hint;
  context.iono = broadcast_navigation().iono;
  return context;
}

TEST(WholeMilliseconds, ReferenceOnItsPredictionOthersNearestTheirs) {
  const double L = kCodePeriodRange_m;
  // True pseudoranges 70.2, 68.9 and 75.6 ms with a clock offset of 0.3 ms: measured modulo 1 ms.
  const std::vector<double> truth_ms = {70.2 + 0.3, 68.9 + 0.3, 75.6 + 0.3};
  std::vector<double> submillisecond;
  for (double t : truth_ms) submillisecond.push_back(std::fmod(t, 1.0) * L);
  // Predictions (less the clock) off by up to 100 km, the reference by 40 km.
  const std::vector<double> predicted = {70.2 * L + 40e3, 68.9 * L - 60e3, 75.6 * L + 100e3};
  const WholeMilliseconds ms = resolve_whole_milliseconds(submillisecond, predicted, 0);
  ASSERT_EQ(ms.milliseconds.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(ms.milliseconds[k] * L + submillisecond[k], truth_ms[k] * L, 1e-6) << k;
  EXPECT_NEAR(ms.clock_bias_m, 0.3 * L - 40e3, 1e-6);
  // Off by more than half a code period relative to the reference: a wrong whole millisecond.
  const std::vector<double> too_far = {70.2 * L - 20e3, 68.9 * L + 140e3, 75.6 * L};
  EXPECT_EQ(resolve_whole_milliseconds(submillisecond, too_far, 0).milliseconds[1], 70);
}

TEST(CoarseTimeFit, ExactCodePhasesGiveThePositionAndTheTimeError) {
  SceneSpec spec;
  spec.place = test_places()[0];
  spec.code_noise_m = 0.0;
  const Scene s = make_scene(spec);
  for (double time_error_s : {0.0, 60.0, -60.0}) {
    const GpsTime hint = s.t_receiver.plus_seconds(time_error_s);
    const auto sats = fit_satellites(s, hint);
    const CoarseTimeContext context = context_at(hint);
    CoarseTimeState start;
    start.r_ecef_m = moved(s.r_true, 30e3, 1.0);
    const WholeMilliseconds ms = resolve_whole_milliseconds(sats, context, start);
    const CoarseTimeFit fit = fit_coarse_time(sats, ms, context, start, 20);
    ASSERT_TRUE(fit.converged) << fit.reason;
    EXPECT_LT((fit.state.r_ecef_m - s.r_true).norm(), 0.05) << time_error_s;
    // True receive time = t_true; the hint is t_true + clock bias + time error.
    EXPECT_NEAR(fit.state.time_correction_s, -(spec.clock_bias_s + time_error_s), 1e-5);
    EXPECT_NEAR(std::remainder(fit.state.clock_bias_m - gps::kSpeedOfLight_mps * spec.clock_bias_s, kCodePeriodRange_m),
                0.0, 0.05);
    EXPECT_LT(fit.residuals_m.cwiseAbs().maxCoeff(), 0.05);
    EXPECT_EQ(fit.H.cols(), 5);
  }
}

TEST(CoarseTimeFit, AFitThatLeavesTheEarthIsReportedAsDiverged) {
  SceneSpec spec;
  spec.place = test_places()[1];
  const Scene s = make_scene(spec);
  const auto sats = fit_satellites(s, s.t_receiver);
  const CoarseTimeContext context = context_at(s.t_receiver);
  CoarseTimeState start;
  start.r_ecef_m = s.r_true;
  WholeMilliseconds ms = resolve_whole_milliseconds(sats, context, start);
  // Whole milliseconds scattered by tens: no place on Earth has such ranges.
  for (std::size_t k = 0; k < ms.milliseconds.size(); ++k) ms.milliseconds[k] += static_cast<int>(17 * k * k) % 41;
  const CoarseTimeFit fit = fit_coarse_time(sats, ms, context, start, 20);
  EXPECT_FALSE(fit.converged);
  EXPECT_FALSE(fit.reason.empty());
}

}  // namespace
}  // namespace deepnav
