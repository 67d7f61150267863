#pragma once
// What a snapshot of IF gives a coarse-time fix (receiver/pvt/coarse_time_solver.hpp): per
// satellite the code phase at one receive sample, which is the transmit time modulo 1 ms,
// and optionally the carrier Doppler and C/N0. No transmit time of week is decoded, so
// the whole milliseconds of each pseudorange are unknown.
//
// The sub-millisecond pseudorange is taken against the approximate time of the sample:
//   z = c (t_hint - t_sv) modulo c * 1 ms, in [0, c * 1 ms)
// (t_sv = the satellite's clock time at transmission, the code phase / 1.023 MHz modulo
// 1 ms). The full pseudorange is then z + N c * 1 ms for a whole number N of milliseconds,
// and its common offset (the receiver clock bias) equals c (t_hint - t_receive) modulo
// c * 1 ms: a hint that is off by whole seconds leaves it unchanged.
#include <map>
#include <optional>
#include <vector>

#include "ins/gps_time.hpp"
#include "signals/ephemeris.hpp"

namespace deepnav {

struct SnapshotMeasurement {
  int prn = 0;
  double code_phase_chips = 0.0;     ///< transmit time modulo 1 ms at the receive sample, chips in [0, 1023)
  std::optional<double> doppler_hz;  ///< carrier Doppler (positive when approaching), when measured
  double cn0_dbhz = 45.0;
};

/// c * 1 ms: the range of one code period (m), the ambiguity of a code-phase pseudorange.
inline constexpr double kCodePeriodRange_m = 299792.458;

/// z = c (t_hint - t_sv) modulo c * 1 ms, with t_sv modulo 1 ms = code_phase_chips / 1.023 MHz.
double submillisecond_pseudorange_m(double code_phase_chips, const GpsTime& t_hint);

/// Throws std::invalid_argument naming the measurement and field when a PRN is outside
/// 1..32 or repeated, a code phase is outside [0, 1023) chips, or a Doppler or C/N0 is not
/// a finite number.
void check_snapshot_measurements(const std::vector<SnapshotMeasurement>& measurements);

}  // namespace deepnav
