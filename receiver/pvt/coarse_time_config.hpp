#pragma once
// Settings of the coarse-time fix (receiver/pvt/coarse_time_solver.hpp) and the reasons
// for their defaults.
#include "receiver/pvt/coarse_time_integrity.hpp"
#include "receiver/pvt/doppler_position.hpp"
#include "receiver/pvt/range_weight.hpp"

namespace deepnav {

struct CoarseTimeConfig {
  /// Code-phase noise (1 sigma, as a range) at `reference_cn0_dbhz`; it grows as
  /// 1 / sqrt(C/N0) below it. 5 m suits code phases interpolated from a correlation
  /// peak of a few milliseconds of signal; the RangeErrorModel's elevation terms add the
  /// atmosphere and orbit errors that are left.
  double code_sigma_m = 5.0;
  double reference_cn0_dbhz = 45.0;
  RangeErrorModel range_errors;
  CoarseTimeIntegrityConfig integrity;
  DopplerPositionConfig doppler;

  /// The farthest a fix may lie from the position hint: half a code period of range
  /// (c * 0.5 ms). Farther, the whole milliseconds taken from the hint cannot all be
  /// right, whatever the residuals say.
  double position_hint_tolerance_m = 149.9e3;
  /// The largest coarse-time correction accepted (s). Satellites' range rates differ by
  /// up to ~1 km/s, so a time error uses up to 1 km of the 150 km of the whole
  /// milliseconds per second: beyond ~2 minutes they are no longer safe.
  double time_hint_tolerance_s = 120.0;

  /// Without a position hint: the spacing of the grids of candidate positions (every
  /// place within 71 km of a candidate, half the tolerance of the whole milliseconds).
  double grid_spacing_m = 100e3;
  /// The global grid (no Doppler position) tries thousands of whole-millisecond sets: it
  /// needs two degrees of freedom so that a wrong set cannot pass the test by chance.
  int min_grid_satellites = 7;
  /// The grid around a Doppler position covers 3 sigma of it, within these bounds (m).
  double min_doppler_search_radius_m = 100e3;
  double max_doppler_search_radius_m = 500e3;

  /// A fix outside these heights (WGS-84, m) is no fix: receivers that take snapshots are
  /// on the ground or in aircraft, and a wrong set of whole milliseconds tends to put the
  /// fix far up or down.
  double min_height_m = -1000.0;
  double max_height_m = 20000.0;
  /// Every satellite used must be above this elevation at the fix (its signal was
  /// received): a fix below a satellite's horizon is a wrong one.
  double min_elevation_rad = -5.0 * 3.14159265358979323846 / 180.0;

  /// When a fix from the hints fails, how far from the time hint (s, each way) the
  /// diagnosis looks for the time at which the code phases fit the position hint.
  double time_scan_s = 6.0 * 3600.0;
};

}  // namespace deepnav
