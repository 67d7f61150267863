#pragma once
// A coarse-time fix as a PvtSolution, so that the products' writers (NMEA, KML, GPX:
// receiver/products) write snapshot fixes as they write a run's.
#include <map>

#include "receiver/pvt/coarse_time_solver.hpp"
#include "receiver/pvt/pvt_solver.hpp"

namespace deepnav {

/// The fix at its receive time, static (no velocity); azimuths from `ephemerides`
/// (by PRN; those of the used satellites must be there).
PvtSolution pvt_solution_of(const CoarseTimeFix& fix, const std::map<int, Ephemeris>& ephemerides);

}  // namespace deepnav
