#include "receiver/pvt/coarse_time_integrity.hpp"

#include <gtest/gtest.h>

#include "snapshot_scene.hpp"

namespace deepnav {
namespace {

using namespace snapshot_test;

struct Case {
  Scene scene;
  std::vector<CoarseTimeSatellite> sats;
  CoarseTimeContext context;
  CoarseTimeState start;
  WholeMilliseconds ms;
};

Case make_case(const SceneSpec& spec) {
  Case u;
  u.scene = make_scene(spec);
  u.sats = fit_satellites(u.scene, u.scene.t_receiver);
  u.context.t_hint = u.scene.t_receiver;
  u.context.iono = broadcast_navigation().iono;
  u.start.r_ecef_m = u.scene.r_true;
  u.ms = resolve_whole_milliseconds(u.sats, u.context, u.start);
  return u;
}

SceneSpec spec_at(std::size_t place, double min_elevation_deg = 5.0) {
  SceneSpec spec;
  spec.place = test_places()[place];
  spec.min_elevation_rad = min_elevation_deg * kDeg;
  return spec;
}

TEST(CoarseTimeIntegrity, RightWholeMillisecondsPassTheTest) {
  const Case u = make_case(spec_at(3));
  const CheckedCoarseTimeFit f = checked_coarse_time_fit(u.sats, u.ms, u.context, u.start, {});
  ASSERT_TRUE(f.passed) << f.reason;
  EXPECT_EQ(f.test.dof, static_cast<int>(u.sats.size()) - 5);
  EXPECT_LT(f.test.statistic, f.test.threshold);
  EXPECT_TRUE(f.excluded_prns.empty());
  EXPECT_TRUE(f.repaired_ms.empty());
  EXPECT_LT((f.fit.state.r_ecef_m - u.scene.r_true).norm(), 20.0);
}

TEST(CoarseTimeIntegrity, AWrongWholeMillisecondIsRepairedOnAnySatellite) {
  const Case u = make_case(spec_at(3));
  ASSERT_GE(u.sats.size(), 8u);
  for (std::size_t k = 0; k < u.sats.size(); ++k) {
    for (int wrong_by : {1, -1}) {
      WholeMilliseconds ms = u.ms;
      ms.milliseconds[k] += wrong_by;
      const CheckedCoarseTimeFit f = checked_coarse_time_fit(u.sats, ms, u.context, u.start, {});
      ASSERT_TRUE(f.passed) << "PRN " << u.sats[k].prn << ": " << f.reason;
      EXPECT_EQ(f.repaired_ms, (std::map<int, int>{{u.sats[k].prn, -wrong_by}})) << "PRN " << u.sats[k].prn;
      EXPECT_TRUE(f.excluded_prns.empty());
      EXPECT_EQ(f.used.size(), u.sats.size());
      EXPECT_LT((f.fit.state.r_ecef_m - u.scene.r_true).norm(), 20.0);
    }
  }
}

TEST(CoarseTimeIntegrity, ABadCodePhaseIsExcludedNotRepaired) {
  Case u = make_case(spec_at(4));
  ASSERT_GE(u.sats.size(), 8u);
  const int bad = u.sats[2].prn;
  u.sats[2].submillisecond_m += 2000.0;  // a false peak two chips off: no whole millisecond explains it
  const CheckedCoarseTimeFit f = checked_coarse_time_fit(u.sats, u.ms, u.context, u.start, {});
  ASSERT_TRUE(f.passed) << f.reason;
  EXPECT_EQ(f.excluded_prns, std::vector<int>{bad});
  EXPECT_TRUE(f.repaired_ms.empty());
  EXPECT_EQ(f.used.size(), u.sats.size() - 1);
  EXPECT_LT((f.fit.state.r_ecef_m - u.scene.r_true).norm(), 20.0);
}

TEST(CoarseTimeIntegrity, WithSixSatellitesAFaultIsDetectedButNotPinned) {
  const Case u = make_case(spec_at(0, 30.0));
  ASSERT_EQ(u.sats.size(), 6u);
  WholeMilliseconds ms = u.ms;
  ms.milliseconds[1] += 1;
  const CheckedCoarseTimeFit f = checked_coarse_time_fit(u.sats, ms, u.context, u.start, {});
  EXPECT_FALSE(f.passed);
  EXPECT_NE(f.reason.find("one degree of freedom cannot tell which satellite is wrong"), std::string::npos) << f.reason;
}

TEST(CoarseTimeIntegrity, FiveSatellitesCannotBeTested) {
  Case u = make_case(spec_at(0, 30.0));
  u.sats.pop_back();
  u.ms.milliseconds.pop_back();
  const CheckedCoarseTimeFit f = checked_coarse_time_fit(u.sats, u.ms, u.context, u.start, {});
  EXPECT_FALSE(f.passed);
  EXPECT_NE(f.reason.find("no redundancy"), std::string::npos) << f.reason;
}

}  // namespace
}  // namespace deepnav
