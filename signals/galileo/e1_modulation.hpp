#pragma once
// Galileo E1 OS modulation (Galileo OS SIS ICD 2.3.3): the BOC(1,1) and BOC(6,1) square-wave
// subcarriers, the CBOC(6,1,1/11) waveforms of E1-B and E1-C, the composite E1 OS signal and
// replica samples of a spread code on a subcarrier.
//
// The chip phase is in chips from the start of a code chip grid: the subcarriers repeat each
// chip, so only its fractional part matters, and a subcarrier starts each chip at +1
// (sc(t) = sign(sin(2 pi R_sc t)), taken as +1 where the sine is 0 at the start of a half).
#include <cmath>
#include <cstddef>
#include <vector>

#include "signals/galileo/e1_codes.hpp"

namespace deepnav::galileo {

/// CBOC weights (ICD 2.3.3): alpha = sqrt(10/11) on BOC(1,1), beta = sqrt(1/11) on BOC(6,1).
inline const double kCbocAlpha = std::sqrt(10.0 / 11.0);
inline const double kCbocBeta = std::sqrt(1.0 / 11.0);

/// Which waveform a chip is shaped with.
enum class E1Subcarrier {
  kBoc11,    ///< sc_a alone: the BOC(1,1) replica a receiver may track E1 with
  kCbocE1b,  ///< alpha sc_a + beta sc_b: E1-B (data) as transmitted
  kCbocE1c,  ///< alpha sc_a - beta sc_b: E1-C (pilot) as transmitted
};

/// sc(m,1): a square wave of m cycles per chip (m = 1: BOC(1,1)'s sc_a, m = 6: sc_b),
/// +1 in the first half of each cycle, -1 in the second.
double boc_subcarrier(int cycles_per_chip, double chip_phase);

/// The waveform `kind` at `chip_phase` (chips).
double e1_subcarrier(E1Subcarrier kind, double chip_phase);

/// The E1 OS signal's in-phase component (ICD 2.3.3) at `chip_phase` for the spreading levels
/// (+1/-1) of E1-B (code times data symbol) and E1-C (primary times secondary code):
/// (e_B (alpha sc_a + beta sc_b) - e_C (alpha sc_a - beta sc_b)) / sqrt(2).
double e1_composite(int e1b_level, int e1c_level, double chip_phase);

/// `count` samples of `code` shaped by `kind`, the first at code phase `first_chip` (chips,
/// any real: the code repeats every 4092 chips), one sample every `chips_per_sample`.
std::vector<float> e1_replica(const E1CodeChips& code, E1Subcarrier kind, double first_chip, double chips_per_sample,
                              std::size_t count);

}  // namespace deepnav::galileo
