#pragma once
// Ionosphere (Klobuchar) and UTC parameters broadcast in LNAV subframe 4 page 18.
#include <array>

namespace deepnav {

struct IonoParameters {
  std::array<double, 4> alpha{};  ///< s, s/semicircle, s/semicircle^2, s/semicircle^3
  std::array<double, 4> beta{};   ///< s, s/semicircle, ...
  bool valid = false;
};

struct UtcParameters {
  double a0_s = 0.0;
  double a1_sps = 0.0;
  int tot_s = 0;       ///< reference time of UTC data, seconds of week
  int wnt = 0;         ///< UTC reference week number (8 LSBs in LNAV)
  int delta_t_ls = 0;  ///< current leap seconds
  int wn_lsf = 0;
  int dn = 0;
  int delta_t_lsf = 0;
  bool valid = false;
};

}  // namespace deepnav
