#include "receiver/pvt/snapshot_measurement.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "signals/gps_constants.hpp"

namespace deepnav {

double submillisecond_pseudorange_m(double code_phase_chips, const GpsTime& t_hint) {
  // The hint is reduced modulo 1 ms first (exactly): subtracting from the seconds of week
  // would round the difference to their 0.1 ns (3 cm) once more.
  const double hint_fraction_s = std::fmod(t_hint.sow, gps::kCodePeriod_s);
  const double transmit_fraction_s = code_phase_chips / gps::kCodeRate_cps;
  double z_s = std::fmod(hint_fraction_s - transmit_fraction_s, gps::kCodePeriod_s);
  if (z_s < 0.0) z_s += gps::kCodePeriod_s;
  return gps::kSpeedOfLight_mps * z_s;
}

void check_snapshot_measurements(const std::vector<SnapshotMeasurement>& measurements) {
  std::set<int> seen;
  for (std::size_t i = 0; i < measurements.size(); ++i) {
    const SnapshotMeasurement& m = measurements[i];
    if (m.prn < 1 || m.prn > gps::kMaxPrn)
      throw std::invalid_argument(
          fmt::format("snapshot measurement {}: prn {} is outside 1..{}", i, m.prn, gps::kMaxPrn));
    if (!seen.insert(m.prn).second)
      throw std::invalid_argument(fmt::format("snapshot measurement {}: prn {} appears twice", i, m.prn));
    if (!(m.code_phase_chips >= 0.0 && m.code_phase_chips < gps::kCodeLength_chips))
      throw std::invalid_argument(
          fmt::format("snapshot measurement {} (PRN {}): code_phase_chips {} is outside [0, {})", i, m.prn,
                      m.code_phase_chips, gps::kCodeLength_chips));
    if (m.doppler_hz && !std::isfinite(*m.doppler_hz))
      throw std::invalid_argument(fmt::format("snapshot measurement {} (PRN {}): doppler_hz is not finite", i, m.prn));
    if (!std::isfinite(m.cn0_dbhz))
      throw std::invalid_argument(fmt::format("snapshot measurement {} (PRN {}): cn0_dbhz is not finite", i, m.prn));
  }
}

}  // namespace deepnav
