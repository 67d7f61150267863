// The coupling steps both aided navigators take: the fix the INS start takes and the
// navigator's clock at the start, the settings the filter gets, and the tight rows: masked,
// weighed, and each Doppler predicted at its own time.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "aiding/gnss_coupling.hpp"
#include "aiding/measurement_models.hpp"
#include "ins/gps_time.hpp"
#include "receiver/pvt/range_model.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(GnssCoupling, AlignmentFixTakesThePvtWithItsDopSigmasFloored) {
  PvtSolution pvt;
  pvt.r_ecef_m = {-3.0e6, 4.0e6, 3.9e6};
  pvt.v_ecef_mps = {1.0, -2.0, 0.5};
  pvt.clock_bias_m = 120.0;
  pvt.clock_drift_mps = 3.0;
  pvt.dops.hdop = 1.5;
  pvt.dops.vdop = 2.5;
  const GnssFix fix = alignment_fix(pvt, 42.0, 2.0);
  EXPECT_EQ(fix.t_s, 42.0);
  EXPECT_EQ(fix.r_antenna_ecef_m, pvt.r_ecef_m);
  EXPECT_EQ(fix.v_antenna_ecef_mps, pvt.v_ecef_mps);
  EXPECT_EQ(fix.clock_bias_m, 120.0);
  EXPECT_DOUBLE_EQ(fix.horizontal_sigma_m, 3.0);
  EXPECT_DOUBLE_EQ(fix.vertical_sigma_m, 5.0);
  pvt.dops.hdop = pvt.dops.vdop = 0.3;
  const GnssFix good = alignment_fix(pvt, 42.0, 2.0);
  EXPECT_DOUBLE_EQ(good.horizontal_sigma_m, 1.0);
  EXPECT_DOUBLE_EQ(good.vertical_sigma_m, 1.5);
}

TEST(GnssCoupling, TheNavigatorStartsWithTheFixClockCarriedToTheStart) {
  InsStart start;
  start.state.t_s = 10.25;
  start.state.llh = {0.6, 2.2, 100.0};
  start.method = "test";
  GnssFix fix;
  fix.t_s = 10.0;
  fix.clock_bias_m = 500.0;
  fix.clock_drift_mps = 4.0;
  CouplingSettings settings;
  settings.gate_sigma = 3.5;
  settings.troposphere.enabled = true;
  settings.ionosphere.random_walk_per_sqrt_h = 0.3;
  const NavigatorConfig nc = navigator_config(settings);
  EXPECT_EQ(nc.gate_sigma, 3.5);
  EXPECT_TRUE(nc.troposphere.enabled);
  EXPECT_EQ(nc.ionosphere.random_walk_per_sqrt_h, 0.3);
  const AidedNavigator nav = start_navigator(start, fix, nc, 30.0, 0.0);
  EXPECT_DOUBLE_EQ(nav.clock_bias_m(), 500.0 + 4.0 * 0.25 + 30.0);
  EXPECT_DOUBLE_EQ(nav.clock_drift_mps(), 4.0);
  EXPECT_EQ(nav.time_s(), 10.25);
  EXPECT_TRUE(nav.troposphere_state_enabled());
}

/// A navigator at rest on the ground and the satellites of data/brdc0010.22n at 02:00.
struct RangeScene {
  NavData nav_data = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  GpsTime t0 = gps_time_from_calendar(CalendarTime{2022, 1, 1, 2, 0, 0.0});
  AidedNavigator nav{state(), 200.0, 10.0, NavigatorConfig{}, InitialUncertainty{}};

  static NavState state() {
    NavState s;
    s.t_s = 100.0;
    s.llh = {37.5 * kDeg, 127.0 * kDeg, 50.0};
    return s;
  }

  /// Every satellite with an ephemeris, observed with a Doppler `doppler_offset_s` from the epoch.
  RangeEpoch epoch(double doppler_offset_s) const {
    RangeEpoch e{nav.time_s() + 0.5, t0, nav_data.iono, {}};
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn)
      if (const Ephemeris* eph = nav_data.select(prn, t0))
        e.satellites.push_back({SatelliteId{GnssSystem::gps, prn}, *eph, 2.2e7, 40.0, 1000.0, doppler_offset_s, 0.07});
    return e;
  }
};

TEST(GnssCoupling, TightRowsAreMaskedWeighedAndTheirRatesTimedByTheDoppler) {
  const RangeScene scene;
  const RangeEpoch epoch = scene.epoch(-0.05);
  const PseudorangeWeighting weighting{RangeErrorModel{}, 0.25, 1.5};
  const TightRows rows = tight_rows(scene.nav, epoch, AtmosphereModels{}, 10.0 * kDeg, weighting);
  ASSERT_GE(rows.used.size(), 5u);
  ASSERT_GE(rows.below_mask.size(), 1u);
  EXPECT_EQ(rows.used.size() + rows.below_mask.size(), epoch.satellites.size());
  for (const RangeMeasurement& m : rows.below_mask) {
    EXPECT_LT(m.geometry.elevation_rad, 10.0 * kDeg);
    EXPECT_FALSE(m.pseudorange_m.has_value());
  }
  for (const RangeMeasurement& m : rows.used) {
    EXPECT_GE(m.geometry.elevation_rad, 10.0 * kDeg);
    EXPECT_NEAR(m.time_offset_s, 0.5, 1e-12);
    EXPECT_EQ(m.pseudorange_m, std::optional<double>(2.2e7));
    EXPECT_DOUBLE_EQ(m.pseudorange_sigma_m,
                     1.5 * scalar_pseudorange_sigma_m(RangeErrorModel{}, m.geometry.elevation_rad, 40.0, 0.25));
    EXPECT_DOUBLE_EQ(*m.rate_mps, -gps::kL1Wavelength_m * 1000.0);
    EXPECT_EQ(m.rate_sigma_mps, 0.07);
    // The rate's geometry is 50 ms earlier: the satellite that much further back on its orbit.
    ASSERT_TRUE(m.rate_at_own_time);
    EXPECT_NEAR(m.rate_time_offset_s, 0.45, 1e-12);
    const Eigen::Vector3d moved = m.rate_geometry.r_sat_ecef_m - m.geometry.r_sat_ecef_m;
    EXPECT_NEAR((moved + 0.05 * m.geometry.v_sat_ecef_mps).norm(), 0.0, 0.5);
  }
}

TEST(GnssCoupling, ASatelliteWithoutDopplerGivesAPseudorangeRowOnly) {
  const RangeScene scene;
  RangeEpoch epoch = scene.epoch(0.0);
  for (RangeObservation& o : epoch.satellites) o.doppler_hz.reset();
  const TightRows rows = tight_rows(scene.nav, epoch, AtmosphereModels{}, 10.0 * kDeg, {});
  ASSERT_FALSE(rows.used.empty());
  for (const RangeMeasurement& m : rows.used) {
    EXPECT_TRUE(m.pseudorange_m.has_value());
    EXPECT_FALSE(m.rate_mps.has_value());
  }
}

/// When the mixed file's Galileo records are densest.
const GpsTime kGalileoTime = gps_time_from_calendar(CalendarTime{2022, 1, 1, 23, 50, 0.0});

/// The Galileo satellites of the mixed file at 23:50, observed with a Doppler, their
/// pseudoranges (when given) already on the GPS clock.
RangeEpoch galileo_epoch(const RangeScene& scene, const NavData& mixed, std::optional<double> pseudorange_m) {
  RangeEpoch e{scene.nav.time_s(), kGalileoTime, mixed.iono, {}};
  for (int svid = 1; svid <= galileo::kMaxPrn; ++svid)
    if (const auto* eph = select_galileo_ephemeris(mixed, svid, galileo::gst_from_gps_time(kGalileoTime))) {
      RangeObservation o{SatelliteId{GnssSystem::galileo, svid}, *eph, pseudorange_m, 40.0, -800.0, 0.0, 0.05};
      o.offset_sigma_m = 0.6;
      e.satellites.push_back(o);
    }
  return e;
}

TEST(GnssCoupling, GalileoRowsTakeTheirOrbitFromGalileoRecordsAndTheOffsetSigmaInQuadrature) {
  const RangeScene scene;
  const NavData mixed = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/gps_galileo_20220101.rnx");
  const RangeEpoch epoch = galileo_epoch(scene, mixed, 2.4e7);
  const TightRows rows = tight_rows(scene.nav, epoch, AtmosphereModels{}, 5.0 * kDeg, {});
  ASSERT_GE(rows.used.size(), 3u);
  for (const RangeMeasurement& m : rows.used) {
    EXPECT_EQ(m.satellite.system, GnssSystem::galileo);
    // The satellite where its own I/NAV record puts it at the transmit time.
    const auto* eph = select_galileo_ephemeris(mixed, m.satellite.prn, galileo::gst_from_gps_time(kGalileoTime));
    ASSERT_NE(eph, nullptr);
    const double tau = m.geometry.geometric_range_m / gps::kSpeedOfLight_mps;
    const SatelliteState s =
        galileo::satellite_state(*eph, galileo::gst_from_gps_time(kGalileoTime.plus_seconds(-tau)));
    EXPECT_LT((s.r_ecef_m - m.geometry.r_sat_ecef_m).norm(), 3.0e3 * tau + 50.0) << m.satellite.to_string();
    EXPECT_GT(m.geometry.geometric_range_m, 2.3e7);  // MEO at 23 222 km
    EXPECT_DOUBLE_EQ(
        m.pseudorange_sigma_m,
        std::hypot(scalar_pseudorange_sigma_m(RangeErrorModel{}, m.geometry.elevation_rad, 40.0, 1.0), 0.6));
    EXPECT_DOUBLE_EQ(*m.rate_mps, -gps::kL1Wavelength_m * -800.0);
  }
}

TEST(GnssCoupling, AGalileoSatelliteBeforeTheOffsetIsKnownGivesARateRowOnly) {
  const RangeScene scene;
  const NavData mixed = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/gps_galileo_20220101.rnx");
  RangeEpoch epoch = galileo_epoch(scene, mixed, std::nullopt);
  TightRows rows = tight_rows(scene.nav, epoch, AtmosphereModels{}, 5.0 * kDeg, {});
  ASSERT_FALSE(rows.used.empty());
  for (const RangeMeasurement& m : rows.used) {
    EXPECT_FALSE(m.pseudorange_m.has_value());
    EXPECT_TRUE(m.rate_mps.has_value());
  }
  // Neither a pseudorange nor a Doppler: no row at all.
  for (RangeObservation& o : epoch.satellites) o.doppler_hz.reset();
  rows = tight_rows(scene.nav, epoch, AtmosphereModels{}, 5.0 * kDeg, {});
  EXPECT_TRUE(rows.used.empty());
}

}  // namespace
}  // namespace deepnav::aiding
