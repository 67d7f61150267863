#include "aiding/satellite_fault_monitor.hpp"

#include <gtest/gtest.h>

#include <random>

namespace deepnav::aiding {
namespace {

SatelliteId gps(int prn) { return {GnssSystem::gps, prn}; }
SatelliteId galileo(int svid) { return {GnssSystem::galileo, svid}; }

/// One update of eight GPS satellites at t: unit-variance innovations, PRN `faulty` offset by
/// `bias_sigma`; with `galileo_too`, Galileo SVIDs 1-8 beside them, fault-free.
std::vector<SatelliteInnovation> update(std::mt19937_64& rng, int faulty, double bias_sigma, double gate = 5.0,
                                        bool galileo_too = false) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<SatelliteInnovation> rows;
  for (int prn = 1; prn <= 8; ++prn) {
    const double v = n(rng) + (prn == faulty ? bias_sigma : 0.0);
    rows.push_back({gps(prn), v, std::abs(v) > gate});
    if (galileo_too) {
      const double w = n(rng);
      rows.push_back({galileo(prn), w, std::abs(w) > gate});
    }
  }
  return rows;
}

TEST(SatelliteFaultMonitor, ConsistentInnovationsExcludeNothing) {
  SatelliteFaultMonitor m;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 600; ++k) m.add(0.1 * k, update(rng, 0, 0.0));  // 60 s at 10 Hz
  EXPECT_EQ(m.exclusions(), 0);
  EXPECT_TRUE(m.excluded_satellites().empty());
}

TEST(SatelliteFaultMonitor, ABiasUnderTheGateExcludesThatSatelliteAlone) {
  SatelliteFaultMonitor m;
  std::mt19937_64 rng(4);
  for (int k = 0; k < 100; ++k) m.add(0.1 * k, update(rng, 0, 0.0));
  // PRN 5 gains a 4-sigma bias: every row still passes a 5-sigma gate.
  int detected_at = -1;
  for (int k = 100; k < 200; ++k) {
    m.add(0.1 * k, update(rng, 5, 4.0));
    if (detected_at < 0 && m.excluded(gps(5))) detected_at = k;
  }
  ASSERT_GE(detected_at, 100);
  EXPECT_LE(detected_at - 100, 20) << "within two seconds of the fault";
  EXPECT_EQ(m.excluded_satellites(), std::vector<SatelliteId>{gps(5)});
  // The fault clears: the satellite, still watched, comes back after the hold time.
  int readmitted_at = -1;
  for (int k = 200; k < 400; ++k) {
    m.add(0.1 * k, update(rng, 0, 0.0));
    if (readmitted_at < 0 && !m.excluded(gps(5))) readmitted_at = k;
  }
  ASSERT_GT(readmitted_at, 0);
  EXPECT_GE(0.1 * (readmitted_at - detected_at), SatelliteFaultConfig{}.hold_s);
  EXPECT_EQ(m.exclusions(), 1);
}

TEST(SatelliteFaultMonitor, AStepTheGateRejectsExcludesTheSatellite) {
  SatelliteFaultMonitor m;
  std::mt19937_64 rng(5);
  for (int k = 0; k < 50; ++k) m.add(k, update(rng, 0, 0.0));
  // 1 Hz tight updates; a 30 m step on a 1 m row is 30 sigma: every row rejected.
  // One 30-sigma row among the window's five moves their mean beyond 3 sigma: excluded at
  // the first epoch of the step (the gate alone would turn the row away but keep trying).
  m.add(50, update(rng, 2, 30.0));
  EXPECT_TRUE(m.excluded(gps(2)));
  for (int k = 51; k < 56; ++k) m.add(k, update(rng, 2, 30.0));
  EXPECT_TRUE(m.excluded(gps(2))) << "held while the step lasts";
  EXPECT_FALSE(m.excluded(gps(3)));
  m.clear();
  EXPECT_FALSE(m.excluded(gps(2)));
}

TEST(SatelliteFaultMonitor, AGpsFaultLeavesTheGalileoSatelliteOfTheSameNumberIn) {
  SatelliteFaultMonitor m;
  std::mt19937_64 rng(6);
  for (int k = 0; k < 50; ++k) m.add(k, update(rng, 0, 0.0, 5.0, true));
  for (int k = 50; k < 56; ++k) m.add(k, update(rng, 4, 30.0, 5.0, true));
  EXPECT_TRUE(m.excluded(gps(4)));
  EXPECT_FALSE(m.excluded(galileo(4)));
  EXPECT_EQ(m.excluded_satellites(), std::vector<SatelliteId>{gps(4)});
}

}  // namespace
}  // namespace deepnav::aiding
