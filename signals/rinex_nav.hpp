#pragma once
// GPS and Galileo broadcast navigation files: reader for RINEX 2.10/2.11 and 3.0x (GPS and
// Galileo records of mixed files; other systems are skipped), writer for RINEX 3.04 GPS,
// Galileo and mixed navigation files.
#include <iosfwd>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "signals/ephemeris.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/galileo/nequick_parameters.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

struct NavData {
  std::vector<Ephemeris> ephemerides;  ///< GPS records in file order (duplicates kept)
  IonoParameters iono;                 ///< from ION ALPHA/BETA or IONOSPHERIC CORR GPSA/GPSB
  /// From DELTA-UTC (RINEX 2) or TIME SYSTEM CORR GPUT (RINEX 3) and LEAP SECONDS. RINEX
  /// gives the full week number in wnt (not the 8 LSBs LNAV carries). valid is set when
  /// the A0/A1 line was present; delta_t_ls alone comes from LEAP SECONDS.
  UtcParameters utc;
  bool leap_seconds_valid = false;
  /// Galileo records (E) of RINEX 3 files in file order (duplicates kept): I/NAV and F/NAV
  /// data sets alike, told apart by data_sources. week is the GST week (RINEX's continuous
  /// "GAL week" less 1024).
  std::vector<galileo::GalileoEphemeris> galileo_ephemerides;
  galileo::NequickParameters galileo_iono;  ///< IONOSPHERIC CORR GAL
  galileo::GgtoParameters ggto;             ///< TIME SYSTEM CORR GAGP (GST - GPST), wn0g a GST week
  UtcParameters galileo_utc;                ///< TIME SYSTEM CORR GAUT (GST - UTC), wnt a GST week
  double rinex_version = 0.0;
  int skipped_records = 0;  ///< records of other satellite systems (neither GPS nor Galileo) in mixed files
  std::string source;       ///< the file (or stream name) it was read from, for messages

  /// The healthy ephemeris of `prn` with the toe closest to t among those whose fit
  /// interval contains t. Data sets whose transmission time is known and later than t
  /// are used only when no other one qualifies. nullptr when none qualifies.
  const Ephemeris* select(int prn, const GpsTime& t) const;
};

/// The Galileo record of `svid` in use at GST t (what a synthesized satellite broadcasts, what
/// an assisted receiver takes): from E1-B I/NAV (data sources bit 0), healthy on E1-B, toe
/// within 4 hours of t (the ICD's validity of a batch), the toe closest to t. As
/// NavData::select for GPS, a record whose known transmission time is later than t is used
/// only when no other one qualifies (files cut at a time hold few records sent before it).
/// nullptr when none qualifies.
const galileo::GalileoEphemeris* select_galileo_ephemeris(const NavData& nav, int svid, const galileo::GstTime& t);

/// Reads a RINEX 2.10/2.11/3.0x navigation file. Throws std::runtime_error naming the file
/// and line ("brdc0010.22n:123: ...") on a missing, empty, truncated or malformed file.
NavData read_rinex_nav(const std::string& path);
/// Same from a stream; `name` is used in error messages.
NavData read_rinex_nav(std::istream& in, const std::string& name);

/// Writes a RINEX 3.04 navigation file: GPS records and parameters, then Galileo records with
/// the GAL, GAGP and GAUT header lines where present; file type G, E or M (both). The header
/// date is the latest toc in the data (of the GPS records when there are any; not the wall
/// clock), so equal inputs give equal bytes, and a GPS-only file is written as before.
void write_rinex3_nav(std::ostream& out, const NavData& nav, const std::string& program_name);

/// URA index (IS-GPS-200 20.3.3.3.1.3) <-> accuracy in metres as RINEX stores it.
int ura_index_from_metres(double ura_m);
double ura_metres_from_index(int ura_index);

}  // namespace deepnav
