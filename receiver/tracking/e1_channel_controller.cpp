#include "receiver/tracking/e1_channel_controller.hpp"

#include <cmath>

#include "ins/gps_time.hpp"
#include "signals/galileo/galileo_constants.hpp"

namespace deepnav {

std::optional<double> e1_transmit_time_sow(const InavDecoder& decoder, double code_chips) {
  // The time mark dates the start of a code period; the replica's unwrapped code phase
  // counts chips from the start of period 0.
  const std::optional<double> period0_tow = decoder.navigation().tow_at_code_period(0);
  if (!period0_tow) return std::nullopt;
  const double tow = *period0_tow + code_chips / galileo::kE1CodeRate_cps;
  return tow - kSecondsPerWeek * std::floor(tow / kSecondsPerWeek);
}

std::optional<double> e1_transmit_time_sow(const InavDecoder& decoder, const E1CorrelatorEpoch& epoch) {
  return e1_transmit_time_sow(
      decoder, static_cast<double>(epoch.code_period) * galileo::kE1CodeLength_chips + epoch.code_phase_chips);
}

}  // namespace deepnav
