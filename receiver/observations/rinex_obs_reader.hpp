#pragma once
// Reader of RINEX observation files, versions 2.10/2.11 and 3.00-3.05, for GPS L1 C/A:
// C1C L1C D1C S1C (RINEX 3) or C1 L1 D1 S1 (RINEX 2), and for Galileo E1 in RINEX 3 files
// (C1C L1C D1C S1C of the E1-C pilot, as the RINEX writer of receiver/products/ writes
// them; a file whose Galileo types lack C1C has its Galileo satellites skipped). Everything
// else (other systems, other signals) is skipped and counted in the report. Clock jumps
// are looked for in the GPS pseudoranges only.
//
// What recordings contain, and what the reader does with it:
//  - the time system of the epochs (TIME OF FIRST OBS, columns 49-51; blank: the file's
//    system's): GPS, GAL, QZS and IRN tags run with GPS time, BDT tags are 14 s behind it,
//    GLO tags are UTC (GPS time less the LEAP SECONDS record's count); every epoch is put
//    on GPS time, and a system that cannot be (GLO without LEAP SECONDS, an unknown one)
//    is an error naming the record;
//  - loss-of-lock indicator (bit 0 of the LLI digit of any L1 C/A field): kept per
//    satellite (the carrier phase may have slipped); an epoch flagged 1 (power failure
//    since the previous epoch) marks every satellite so;
//  - a missing pseudorange or Doppler: the field stays empty (nullopt), counted;
//  - SYS / SCALE FACTOR (RINEX 3): the stored values divided by it;
//  - receiver clock jumps (a receiver that keeps its clock within a millisecond of GPS
//    time re-sets it by whole milliseconds, and every pseudorange jumps by c x 1 ms; one
//    that steers its time tags steps them by microseconds, hundreds of metres): found
//    from the pseudorange change between epochs against the Doppler's, reported per epoch
//    (ObservationEpoch::clock_jump_m) and in the report; the data are left as recorded;
//  - epoch flags 2-5 (moving antenna, new site, header records, external event): their
//    special records are header records, and those that change how the observation
//    records read (observation types, scale factors) apply from there on; counted;
//  - epoch flag 6 (cycle slip records): read with the epoch's types, skipped, counted;
//  - an epoch written twice (the same time and the same records as the one before it):
//    skipped, counted, warned about;
//  - the nominal interval is the epochs' own spacing (their median interval); a header
//    INTERVAL that disagrees is warned about; gaps (an interval over 1.5 times the
//    nominal one) are reported, never interpolated.
// Errors (not a RINEX observation file, an unsupported version, no GPS C1C/C1 type, a
// malformed epoch or field, a truncated epoch, an epoch at the time of the one before
// with other records, epochs going backwards) throw std::runtime_error naming the file,
// the line and the field.
#include <Eigen/Core>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"

namespace deepnav {

/// One GPS satellite's L1 C/A observables at an epoch (a missing one is nullopt); also a
/// Galileo satellite's E1 ones (the same frequency and observables; prn is the SVID).
struct GpsL1Observation {
  int prn = 0;
  std::optional<double> pseudorange_m;
  std::optional<double> carrier_phase_cycles;  ///< RINEX sign: grows with range
  std::optional<double> doppler_hz;            ///< positive when the satellite approaches
  std::optional<double> cn0_dbhz;
  bool loss_of_lock = false;  ///< LLI bit 0, or the epoch followed a power failure
};

struct ObservationEpoch {
  GpsTime t;     ///< receiver time tag, as recorded
  int line = 0;  ///< line of the epoch record in the file
  int flag = 0;  ///< 0 OK, 1 power failure before this epoch
  std::optional<double> receiver_clock_offset_s;
  std::vector<GpsL1Observation> gps;      ///< satellites with any L1 C/A observable
  std::vector<GpsL1Observation> galileo;  ///< Galileo satellites with any E1 observable
  /// The receiver clock was re-set since the previous epoch: every pseudorange moved by
  /// this much more than the Dopplers say (m; 0 when it was not). clock_jump_m / c is the
  /// step of the clock bias.
  double clock_jump_m = 0.0;
  bool after_gap = false;  ///< more than 1.5 nominal intervals since the previous epoch
};

struct ObservationGap {
  int line = 0;  ///< line of the first epoch after the gap
  GpsTime before, after;
  double seconds = 0.0;
};

struct ClockJump {
  int line = 0;
  GpsTime t;
  double jump_m = 0.0;
  double jump_ms = 0.0;  ///< jump_m / (c x 1 ms), whole for a millisecond reset
};

struct ObservationReport {
  double version = 0.0;
  std::string time_system;                  ///< of the epochs' tags, as the file gives it (now on GPS time)
  int epochs = 0;                           ///< epochs with observations (flags 0 and 1)
  double nominal_interval_s = 0.0;          ///< the median epoch spacing (INTERVAL for a single epoch)
  std::optional<double> header_interval_s;  ///< the INTERVAL record's
  std::optional<Eigen::Vector3d> approx_position_ecef_m;
  std::map<std::string, int> skipped_satellite_records;  ///< by system ("E", "R", "S", "C", "J", "I")
  std::map<std::string, int> skipped_gps_values;         ///< GPS observables of other signals, by type
  std::map<std::string, int> skipped_galileo_values;     ///< Galileo observables of other signals, by type
  int gps_satellite_records = 0;                         ///< GPS satellite records with an L1 C/A observable
  int galileo_satellite_records = 0;                     ///< Galileo satellite records with an E1 observable
  int missing_pseudorange = 0, missing_doppler = 0, missing_phase = 0, missing_cn0 = 0;
  int loss_of_lock = 0;
  int power_failure_epochs = 0;      ///< flag 1
  int event_epochs = 0;              ///< flags 2-5
  int observation_type_changes = 0;  ///< observation type records applied from events
  int cycle_slip_epochs = 0;         ///< flag 6 (their records skipped)
  int repeated_epochs = 0;           ///< epochs written twice (skipped)
  int first_repeated_epoch_line = 0;
  std::vector<ObservationGap> gaps;
  std::vector<ClockJump> clock_jumps;
  /// What a user should know about the file (each names the file and a line).
  std::vector<std::string> warnings;
};

struct ObservationFile {
  std::vector<ObservationEpoch> epochs;
  ObservationReport report;
};

/// Reads a RINEX observation file (see the rules above).
ObservationFile read_rinex_obs(const std::string& path);
/// Same from a stream; `name` is used in error messages.
ObservationFile read_rinex_obs(std::istream& in, const std::string& name);

}  // namespace deepnav
