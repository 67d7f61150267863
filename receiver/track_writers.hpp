#pragma once
// KML (Google Earth) and GPX 1.1 tracks of the fixes of a run.
#include <string>
#include <vector>

#include "receiver/pvt_solver.hpp"

namespace deepnav {

std::string kml_track(const std::vector<PvtSolution>& fixes, const std::string& name);
/// Times are UTC (GPS minus leap_seconds).
std::string gpx_track(const std::vector<PvtSolution>& fixes, const std::string& name, int leap_seconds);

}  // namespace deepnav
