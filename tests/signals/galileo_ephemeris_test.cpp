#include <gtest/gtest.h>

#include <cmath>

#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/gst.hpp"

namespace deepnav::galileo {
namespace {

/// E01's I/NAV batch of 2022-02-19 22:00 GST (data/galileo_20220220.rnx, first record).
GalileoEphemeris e01() {
  GalileoEphemeris eph;
  eph.prn = 1;
  eph.week = 2197 - kGstWeekOffsetFromGps;
  eph.iod_nav = 100;
  eph.toc_s = 597600.0;
  eph.af0_s = -5.823274259456E-04;
  eph.af1_sps = -7.318590178329E-12;
  eph.orbit.toe_s = 597600.0;
  eph.orbit.crs_m = 3.634375000000E+01;
  eph.orbit.delta_n_radps = 3.581577758518E-09;
  eph.orbit.m0_rad = 3.119252175591E+00;
  eph.orbit.cuc_rad = 1.583248376846E-06;
  eph.orbit.e = 2.864745911211E-04;
  eph.orbit.cus_rad = 2.972781658173E-06;
  eph.orbit.sqrt_a = 5.440600259781E+03;
  eph.orbit.cic_rad = -5.029141902924E-08;
  eph.orbit.omega0_rad = 2.132966860803E+00;
  eph.orbit.cis_rad = -8.381903171539E-08;
  eph.orbit.i0_rad = 9.742233313979E-01;
  eph.orbit.crc_m = 2.851250000000E+02;
  eph.orbit.omega_rad = 3.812866368617E-01;
  eph.orbit.omega_dot_radps = -6.031679815103E-09;
  eph.orbit.idot_radps = 1.446488823494E-10;
  eph.bgd_e1e5a_s = 2.328306436539E-10;
  eph.bgd_e1e5b_s = 0.0;
  eph.sisa_index = 107;
  return eph;
}

TEST(GalileoTime, GstWeekIsGpsWeekLess1024) {
  // 2022-02-20 00:00 (GPS time) starts GPS week 2198, GST week 1174.
  const GpsTime gps{2198, 3600.0};
  const GstTime gst = gst_from_gps_time(gps);
  EXPECT_EQ(gst.week, 1174);
  EXPECT_DOUBLE_EQ(gst.tow_s, 3600.0);
  const GpsTime back = gps_time_from_gst(gst);
  EXPECT_EQ(back.week, 2198);
  EXPECT_DOUBLE_EQ(back.sow, 3600.0);
  // GST week 0 begins at GPS week 1024.
  EXPECT_EQ(gps_time_from_gst({0, 0.0}).week, 1024);
  // A GGTO moves the label by its value; across a week boundary the week carries.
  const GstTime shifted = gst_from_gps_time(GpsTime{2198, 604799.99999999}, 30e-9);
  EXPECT_EQ(shifted.week, 1175);
  EXPECT_NEAR(shifted.tow_s, 0.0, 1e-6);
  const GstTime later{1174, 10.0}, earlier{1173, 604790.0};
  EXPECT_NEAR(later.seconds_since(earlier), 20.0, 1e-9);
}

TEST(GalileoTime, GgtoFollowsTheIcdFormula) {
  // GAGP of data/galileo_20220220.rnx: a0, a1, t0G = 86400, week 2198 (GPS numbering).
  GgtoParameters g{5.9080775827E-09, 3.552713679E-15, 86400, 2198 - kGstWeekOffsetFromGps, true};
  EXPECT_NEAR(gst_minus_gpst_s(g, {1174, 86400.0}), 5.9080775827E-09, 1e-20);
  EXPECT_NEAR(gst_minus_gpst_s(g, {1174, 86400.0 + 1e4}), 5.9080775827E-09 + 3.552713679E-15 * 1e4, 1e-20);
  // A week later, with WN0G as broadcast (6 bits): the same as with the full week.
  GgtoParameters six_bits = g;
  six_bits.wn0g = g.wn0g % 64;
  EXPECT_NEAR(gst_minus_gpst_s(six_bits, {1175, 100.0}), gst_minus_gpst_s(g, {1175, 100.0}), 1e-20);
  EXPECT_NEAR(gst_minus_gpst_s(g, {1175, 100.0}), 5.9080775827E-09 + 3.552713679E-15 * (604800.0 + 100 - 86400), 1e-20);
  // Reference in the week after t (WN0G ahead by one, modulo 64).
  EXPECT_NEAR(gst_minus_gpst_s(six_bits, {1173, 86400.0}), 5.9080775827E-09 - 3.552713679E-15 * 604800.0, 1e-20);
}

TEST(GalileoEphemeris, ConstantsAreTheIcds) {
  EXPECT_NEAR(kRelativisticF, -2.0 * std::sqrt(kGM_m3ps2) / (gps::kSpeedOfLight_mps * gps::kSpeedOfLight_mps), 1e-18);
  EXPECT_NE(kGM_m3ps2, gps::kGM_m3ps2);
}

TEST(GalileoEphemeris, OrbitIsAGalileoOrbit) {
  const GalileoEphemeris eph = e01();
  const GstTime toe{eph.week, eph.orbit.toe_s};
  for (double dt : {-7200.0, 0.0, 1800.0, 7200.0}) {
    const SatelliteState st = satellite_state(eph, GstTime::normalized(toe.week, toe.tow_s + dt));
    // About 29 600 km from the geocentre, 3.6 km/s inertial (less in ECEF).
    EXPECT_NEAR(st.r_ecef_m.norm(), 29.6e6, 0.1e6) << dt;
    EXPECT_GT(st.v_ecef_mps.norm(), 2.5e3) << dt;
    EXPECT_LT(st.v_ecef_mps.norm(), 4.0e3) << dt;
    // The velocity is the derivative of the position.
    const double h = 0.5;
    const Eigen::Vector3d numeric = (satellite_state(eph, GstTime::normalized(toe.week, toe.tow_s + dt + h)).r_ecef_m -
                                     satellite_state(eph, GstTime::normalized(toe.week, toe.tow_s + dt - h)).r_ecef_m) /
                                    (2 * h);
    EXPECT_LT((numeric - st.v_ecef_mps).norm(), 1e-3) << dt;
  }
}

TEST(GalileoEphemeris, ClockWithRelativityAndTheE5bGroupDelay) {
  GalileoEphemeris eph = e01();
  eph.af2_sps2 = 1e-18;
  eph.bgd_e1e5b_s = 3.0e-9;
  const GstTime t{eph.week, eph.toc_s + 1000.0};
  const SatelliteState st = satellite_state(eph, t);
  const double polynomial = eph.af0_s + eph.af1_sps * 1000.0 + eph.af2_sps2 * 1e6;
  EXPECT_NEAR(st.clock_bias_s - st.relativistic_s, polynomial, 1e-18);
  // e = 2.9e-4: the relativistic term is at most F e sqrt(A), about 0.7 ns.
  EXPECT_LE(std::abs(st.relativistic_s), std::abs(kRelativisticF) * eph.orbit.e * eph.orbit.sqrt_a + 1e-20);
  EXPECT_NEAR(e1_clock_correction_s(eph, t), st.clock_bias_s - 3.0e-9, 1e-18);
  // An F/NAV data set's clock refers to E1,E5a: its own group delay applies.
  GalileoEphemeris fnav = eph;
  fnav.data_sources = 258;  // F/NAV E5a-I, clock for E5a,E1
  EXPECT_NEAR(e1_clock_correction_s(fnav, t), st.clock_bias_s - eph.bgd_e1e5a_s, 1e-18);
  // toc in the previous week still works (weeks count).
  const GstTime next_week{eph.week + 1, 100.0};
  EXPECT_NEAR(satellite_state(eph, next_week).clock_bias_s - satellite_state(eph, next_week).relativistic_s,
              eph.af0_s + eph.af1_sps * (604800.0 + 100.0 - eph.toc_s) +
                  eph.af2_sps2 * std::pow(604800.0 + 100.0 - eph.toc_s, 2),
              1e-15);
}

TEST(GalileoEphemeris, SisaTable) {
  EXPECT_DOUBLE_EQ(*sisa_metres(0), 0.0);
  EXPECT_DOUBLE_EQ(*sisa_metres(49), 0.49);
  EXPECT_DOUBLE_EQ(*sisa_metres(50), 0.50);
  EXPECT_DOUBLE_EQ(*sisa_metres(74), 0.98);
  EXPECT_DOUBLE_EQ(*sisa_metres(75), 1.00);
  EXPECT_DOUBLE_EQ(*sisa_metres(99), 1.96);
  EXPECT_DOUBLE_EQ(*sisa_metres(100), 2.00);
  EXPECT_NEAR(*sisa_metres(107), 3.12, 1e-12);
  EXPECT_NEAR(*sisa_metres(125), 6.00, 1e-12);
  EXPECT_FALSE(sisa_metres(126));
  EXPECT_FALSE(sisa_metres(255));
  EXPECT_EQ(sisa_index_from_metres(3.12), 107);
  EXPECT_EQ(sisa_index_from_metres(0.0), 0);
  EXPECT_EQ(sisa_index_from_metres(-1.0), 255);  // RINEX's "unknown"
  EXPECT_EQ(sisa_index_from_metres(6.01), 255);
  for (int i = 0; i <= 125; ++i) EXPECT_EQ(sisa_index_from_metres(*sisa_metres(i)), i) << i;
}

TEST(GalileoEphemeris, HealthOfE1b) {
  GalileoEphemeris eph = e01();
  EXPECT_TRUE(eph.healthy_on_e1b());
  eph.e1b.data_invalid = true;
  EXPECT_FALSE(eph.healthy_on_e1b());
  eph.e1b = {static_cast<int>(SignalHealth::kInTest), false};
  EXPECT_FALSE(eph.healthy_on_e1b());
  eph.e1b = {};
  eph.e5a = {static_cast<int>(SignalHealth::kOutOfService), true};  // another signal's status
  EXPECT_TRUE(eph.healthy_on_e1b());
}

}  // namespace
}  // namespace deepnav::galileo
