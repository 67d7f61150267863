#include "aiding/innovation_monitor.hpp"

#include <gtest/gtest.h>

namespace deepnav::aiding {
namespace {

KalmanUpdate rows(int offered, int rejected) {
  KalmanUpdate r;
  r.rows = offered;
  r.rejected = rejected;
  return r;
}

TEST(InnovationMonitor, FlagsAFilterWhoseGateRejectsMostRowsOverTheWindow) {
  InnovationMonitor m({3.0, 15, 0.2});
  // Tight coupling's pace: 16 rows a second, a stray rejection now and then.
  for (int k = 0; k < 10; ++k) m.add(k, rows(16, k % 4 == 0 ? 1 : 0));
  EXPECT_FALSE(m.inconsistent());
  // The filter stops agreeing with the signals: half the rows fail the gate.
  m.add(10.0, rows(16, 8));
  EXPECT_FALSE(m.inconsistent()) << "one bad update among three seconds of good ones";
  m.add(11.0, rows(16, 8));
  m.add(12.0, rows(16, 8));
  EXPECT_TRUE(m.inconsistent());
  EXPECT_EQ(m.rows(), 48);  // the window holds t = 10, 11, 12 only
  EXPECT_EQ(m.rejected(), 24);
  m.clear();
  EXPECT_FALSE(m.inconsistent());
  EXPECT_EQ(m.rows(), 0);
}

TEST(InnovationMonitor, TooFewRowsSayNothing) {
  InnovationMonitor m({3.0, 15, 0.2});
  m.add(0.0, rows(6, 6));  // one loose update, all rejected
  m.add(1.0, rows(6, 6));
  EXPECT_FALSE(m.inconsistent());
  m.add(2.0, rows(6, 6));
  EXPECT_TRUE(m.inconsistent());
  m.add(2.5, KalmanUpdate{});  // an update that offered nothing changes nothing
  EXPECT_TRUE(m.inconsistent());
}

}  // namespace
}  // namespace deepnav::aiding
