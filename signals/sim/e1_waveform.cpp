#include "signals/sim/e1_waveform.hpp"

#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/e1_modulation.hpp"
#include "signals/sim/satellite_signal_kernel.hpp"

namespace deepnav {

E1WaveformTables::E1WaveformTables(int prn) {
  const galileo::E1CodeChips& b = galileo::e1b_code_chips(prn);
  const galileo::E1CodeChips& c = galileo::e1c_code_chips(prn);
  const std::size_t entries = static_cast<std::size_t>(galileo::kE1CodeLength_chips) * kE1SubchipsPerChip;
  same.resize(entries);
  opposite.resize(entries);
  for (std::size_t j = 0; j < entries; ++j) {
    const std::size_t chip = j / kE1SubchipsPerChip;
    // The middle of the twelfth: away from the subcarrier's transitions at its edges.
    const double phase = (static_cast<double>(j % kE1SubchipsPerChip) + 0.5) / kE1SubchipsPerChip;
    same[j] = static_cast<float>(galileo::e1_composite(b[chip], c[chip], phase));
    opposite[j] = static_cast<float>(galileo::e1_composite(b[chip], -c[chip], phase));
  }
}

}  // namespace deepnav
