#pragma once
// The ionosphere parameters Galileo broadcasts for the NeQuick G model (Galileo OS SIS ICD
// 5.1.6; I/NAV word type 5, RINEX "IONOSPHERIC CORR" GAL).
#include <array>

namespace deepnav::galileo {

/// The effective ionisation level coefficients and the disturbance flags of the five regions.
struct NequickParameters {
  double ai0_sfu = 0.0;
  double ai1_sfu_per_deg = 0.0;
  double ai2_sfu_per_deg2 = 0.0;
  std::array<bool, 5> region_disturbed{};
  bool valid = false;
};

}  // namespace deepnav::galileo
