#pragma once
// KML (Google Earth) and GPX 1.1 tracks of the fixes of a run, in pieces so a run can
// write them as it goes: the header, one point per fix, the footer.
#include <string>
#include <vector>

#include "receiver/pvt/pvt_solver.hpp"

namespace deepnav {

std::string kml_header(const std::string& name);
std::string kml_point(const PvtSolution& fix);
std::string kml_footer();
std::string gpx_header(const std::string& name);
/// Times are UTC (GPS minus leap_seconds).
std::string gpx_point(const PvtSolution& fix, int leap_seconds);
std::string gpx_footer();

/// Whole tracks (header, points, footer).
std::string kml_track(const std::vector<PvtSolution>& fixes, const std::string& name);
std::string gpx_track(const std::vector<PvtSolution>& fixes, const std::string& name, int leap_seconds);

}  // namespace deepnav
