#pragma once
// The jamming benchmark's verdict on one point: from the figures of its jammed window
// (per-satellite tracking, the solutions' error and availability) to the summary over the
// channels and whether, and why, the point failed. A pure function of its figures.
#include <map>
#include <optional>
#include <string>

namespace deepnav::bench {

/// Thresholds that make a point a failure: the solution leaves 10 m (horizontal or
/// vertical, any solution, an aided mode's INS coast included), GNSS fixes (not in INS
/// coast, at least four satellites tracked) are missing for more than 5 % of the jammed
/// epochs, or the channels are tracked for less than half of the jammed time on average.
struct FailureCriteria {
  double max_error_m = 10.0;
  double min_fix_availability = 0.95;
  double min_tracked_fraction = 0.5;
};

/// One satellite over the jammed window.
struct JamChannelFigures {
  double tracked_fraction = 0.0;   ///< of the window, under the receiver's loss rule
  double signal_fraction = 0.0;    ///< of the window, following with C/N0 above the signal floor
  std::optional<double> cn0_dbhz;  ///< mean estimate while tracked; none: never tracked after settling
};

/// Per satellite, keyed as point.json keys them (a GPS PRN as text: "1", "10", "2", ...; a
/// Galileo satellite as "E11"), so
/// the means over channels add up in the order of the record they are written beside.
using JamChannels = std::map<std::string, JamChannelFigures>;

/// The solutions in the jammed window. Every solution counts for the error (an aided
/// mode's coasting INS included); only GNSS fixes (not in INS coast, at least four
/// satellites tracked) count for fix availability.
struct JamSolutionFigures {
  int solutions = 0, fixes = 0;
  double solution_availability = 0.0, fix_availability = 0.0;  ///< over the epochs expected (1 Hz)
  /// Epochs per navigation mode ("none": expected epochs without a solution).
  std::map<std::string, double> epochs_in_mode;
  std::optional<double> horizontal_rms_m, horizontal_max_m, vertical_rms_m, vertical_max_m;  ///< none: no solution
};

struct JamVerdict {
  double tracked_fraction_mean = 0.0, tracked_fraction_min = 0.0;  ///< 0 without channels
  double signal_fraction_mean = 0.0;
  std::optional<double> cn0_mean_dbhz;  ///< over the channels with an estimate
  bool failed = false;
  std::string failure;  ///< every criterion missed, "; "-separated ("" when passed)
};

JamVerdict judge_jam_point(const JamChannels& channels, const JamSolutionFigures& solution,
                           const FailureCriteria& criteria = {});

}  // namespace deepnav::bench
