#pragma once
// Receiver antenna gain by elevation, relative to the zenith. The scenario's C/N0 is
// what an isotropic antenna would see; a real patch antenna loses several dB towards
// the horizon, which is what makes low satellites weak (and later, multipath-prone).
namespace deepnav {

struct AntennaSpec {
  enum class Pattern { isotropic, patch };
  Pattern pattern = Pattern::isotropic;
  /// patch: gain at 10 deg and at the horizon, dB relative to the zenith (0 > 10 deg > horizon).
  double gain_10deg_db = -5.0;
  double gain_horizon_db = -10.0;

  bool operator==(const AntennaSpec&) const = default;
};

/// Gain (dB, 0 at the zenith) at an elevation (rad, below 0 taken as 0). patch:
/// g(el) = g_horizon (1 - sin el)^p with p such that g(10 deg) = gain_10deg_db: smooth and
/// monotonic, through the three points of a typical L1 patch (0 dB at the zenith, about
/// -5 dB at 10 deg, -10 dB at the horizon); -2.2 dB at 20 deg, -0.8 dB at 30 deg.
double antenna_gain_db(const AntennaSpec& spec, double elevation_rad);

}  // namespace deepnav
