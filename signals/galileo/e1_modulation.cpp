#include "signals/galileo/e1_modulation.hpp"

#include <stdexcept>

namespace deepnav::galileo {
namespace {

/// Fraction of a chip in [0, 1) at any chip phase, negative ones included.
double chip_fraction(double chip_phase) { return chip_phase - std::floor(chip_phase); }

}  // namespace

double boc_subcarrier(int cycles_per_chip, double chip_phase) {
  if (cycles_per_chip < 1) throw std::invalid_argument("BOC subcarrier: cycles per chip must be at least 1");
  // Half-cycles since the chip started: even ones are +1.
  const double half_cycles = 2.0 * cycles_per_chip * chip_fraction(chip_phase);
  return static_cast<long>(std::floor(half_cycles)) % 2 == 0 ? 1.0 : -1.0;
}

double e1_subcarrier(E1Subcarrier kind, double chip_phase) {
  switch (kind) {
    case E1Subcarrier::kBoc11:
      return boc_subcarrier(1, chip_phase);
    case E1Subcarrier::kCbocE1b:
      return kCbocAlpha * boc_subcarrier(1, chip_phase) + kCbocBeta * boc_subcarrier(6, chip_phase);
    case E1Subcarrier::kCbocE1c:
      return kCbocAlpha * boc_subcarrier(1, chip_phase) - kCbocBeta * boc_subcarrier(6, chip_phase);
  }
  throw std::invalid_argument("E1 subcarrier: unknown kind");
}

double e1_composite(int e1b_level, int e1c_level, double chip_phase) {
  const double data = e1b_level * e1_subcarrier(E1Subcarrier::kCbocE1b, chip_phase);
  const double pilot = e1c_level * e1_subcarrier(E1Subcarrier::kCbocE1c, chip_phase);
  return (data - pilot) / std::sqrt(2.0);
}

std::vector<float> e1_replica(const E1CodeChips& code, E1Subcarrier kind, double first_chip, double chips_per_sample,
                              std::size_t count) {
  std::vector<float> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    // Each sample's phase from the first one's (no accumulated rounding over long replicas).
    const double phase = first_chip + static_cast<double>(i) * chips_per_sample;
    const double chip = std::floor(phase);
    const double wrapped = chip - kE1CodeLength_chips * std::floor(chip / kE1CodeLength_chips);
    const auto index = static_cast<std::size_t>(wrapped);
    out[i] = static_cast<float>(code[index] * e1_subcarrier(kind, phase));
  }
  return out;
}

}  // namespace deepnav::galileo
