#pragma once
// E01's I/NAV batch of 2022-02-19 22:00 (data/galileo_20220220.rnx): the orbit, clock and
// SISA a satellite sent, printed to 13 digits, so within rounding of multiples of the I/NAV
// fields' LSBs. The message tests of the signal layer and the receiver's decoder tests both
// encode it; the group delays travel in word 5, which each test sets itself.
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

}  // namespace deepnav::testing
