#pragma once
// E01's I/NAV batch of 2022-02-19 22:00 (data/galileo_20220220.rnx): the orbit, clock and
// SISA a satellite sent, printed to 13 digits, so within rounding of multiples of the I/NAV
// fields' LSBs. The message tests of the signal layer and the receiver's decoder tests both
// encode it; the group delays travel in word 5, which each test sets itself.
#include <gtest/gtest.h>

#include "signals/galileo/galileo_ephemeris.hpp"

namespace deepnav::testing {

inline galileo::GalileoEphemeris e01_inav_batch() {
  galileo::GalileoEphemeris eph;
  eph.week = 1173;
  eph.iod_nav = 100;
  eph.toc_s = 597600.0;
  eph.af0_s = -5.823274259456E-04;
  eph.af1_sps = -7.318590178329E-12;
  KeplerElements& o = eph.orbit;
  o.toe_s = 597600.0;
  o.crs_m = 3.634375000000E+01;
  o.delta_n_radps = 3.581577758518E-09;
  o.m0_rad = 3.119252175591E+00;
  o.cuc_rad = 1.583248376846E-06;
  o.e = 2.864745911211E-04;
  o.cus_rad = 2.972781658173E-06;
  o.sqrt_a = 5.440600259781E+03;
  o.cic_rad = -5.029141902924E-08;
  o.omega0_rad = 2.132966860803E+00;
  o.cis_rad = -8.381903171539E-08;
  o.i0_rad = 9.742233313979E-01;
  o.crc_m = 2.851250000000E+02;
  o.omega_rad = 3.812866368617E-01;
  o.omega_dot_radps = -6.031679815103E-09;
  o.idot_radps = 1.446488823494E-10;
  eph.sisa_index = 107;
  eph.prn = 1;
  return eph;
}

/// Every field of two Galileo ephemerides equal (EXPECT_EQ each, so a failure names the field).
inline void expect_same_galileo_ephemeris(const galileo::GalileoEphemeris& a, const galileo::GalileoEphemeris& b) {
  EXPECT_EQ(a.prn, b.prn);
  EXPECT_EQ(a.week, b.week);
  EXPECT_EQ(a.iod_nav, b.iod_nav);
  EXPECT_EQ(a.toc_s, b.toc_s);
  EXPECT_EQ(a.af0_s, b.af0_s);
  EXPECT_EQ(a.af1_sps, b.af1_sps);
  EXPECT_EQ(a.af2_sps2, b.af2_sps2);
  EXPECT_EQ(a.bgd_e1e5a_s, b.bgd_e1e5a_s);
  EXPECT_EQ(a.bgd_e1e5b_s, b.bgd_e1e5b_s);
  EXPECT_EQ(a.sisa_index, b.sisa_index);
  EXPECT_EQ(a.e1b.health, b.e1b.health);
  EXPECT_EQ(a.e1b.data_invalid, b.e1b.data_invalid);
  EXPECT_EQ(a.e5a.health, b.e5a.health);
  EXPECT_EQ(a.e5b.health, b.e5b.health);
  EXPECT_EQ(a.data_sources, b.data_sources);
  EXPECT_EQ(a.transmission_time_known, b.transmission_time_known);
  EXPECT_EQ(a.transmission_time_s, b.transmission_time_s);
  const KeplerElements &x = a.orbit, &y = b.orbit;
  EXPECT_EQ(x.toe_s, y.toe_s);
  EXPECT_EQ(x.sqrt_a, y.sqrt_a);
  EXPECT_EQ(x.e, y.e);
  EXPECT_EQ(x.m0_rad, y.m0_rad);
  EXPECT_EQ(x.delta_n_radps, y.delta_n_radps);
  EXPECT_EQ(x.omega0_rad, y.omega0_rad);
  EXPECT_EQ(x.omega_dot_radps, y.omega_dot_radps);
  EXPECT_EQ(x.i0_rad, y.i0_rad);
  EXPECT_EQ(x.idot_radps, y.idot_radps);
  EXPECT_EQ(x.omega_rad, y.omega_rad);
  EXPECT_EQ(x.cuc_rad, y.cuc_rad);
  EXPECT_EQ(x.cus_rad, y.cus_rad);
  EXPECT_EQ(x.crc_m, y.crc_m);
  EXPECT_EQ(x.crs_m, y.crs_m);
  EXPECT_EQ(x.cic_rad, y.cic_rad);
  EXPECT_EQ(x.cis_rad, y.cis_rad);
}

}  // namespace deepnav::testing
