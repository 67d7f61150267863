#pragma once
// Galileo E1 ranging codes (Galileo OS SIS ICD 3.4): the 4092-chip E1-B and E1-C primary
// memory codes of PRNs 1..50 and the E1-C secondary code CS25. Logic 0 is the signal level
// +1 and logic 1 is -1 (ICD Table 11), as for GPS.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "signals/galileo/galileo_constants.hpp"

namespace deepnav::galileo {

/// One primary code period as signal levels (+1/-1), chip 0 first.
using E1CodeChips = std::array<std::int8_t, kE1CodeLength_chips>;
using E1SecondaryChips = std::array<std::int8_t, kE1cSecondaryLength_chips>;

/// Levels of the E1-B (data) primary code of a PRN in 1..50; cached, cheap to call again.
/// Throws std::invalid_argument naming the PRN otherwise.
const E1CodeChips& e1b_code_chips(int prn);
/// Levels of the E1-C (pilot) primary code of a PRN in 1..50; as e1b_code_chips.
const E1CodeChips& e1c_code_chips(int prn);

/// CS25, the E1-C secondary code (ICD Table 16: hexadecimal 380AD90 of 25 bits), which
/// multiplies successive E1-C primary code periods: 100 ms of tiered code.
const E1SecondaryChips& e1c_secondary_chips();

/// Levels of a memory code written as the ICD prints it: hexadecimal digits, the first chip
/// in the most significant bit of the first digit, `chips` chips in all (the last digit's
/// unused low bits, where chips is not a multiple of 4, must be zero). Throws
/// std::invalid_argument naming `what` for a wrong length or a non-hexadecimal digit.
std::vector<std::int8_t> chips_from_hex(std::string_view hex, int chips, std::string_view what);

}  // namespace deepnav::galileo
