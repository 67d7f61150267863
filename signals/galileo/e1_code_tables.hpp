#pragma once
// The E1-B and E1-C primary codes as hexadecimal text (Galileo OS SIS ICD Annex C); read them
// through signals/galileo/e1_codes.hpp, which turns them into chips.
#include <array>
#include <string_view>

namespace deepnav::galileo::detail {

inline constexpr int kE1PrimaryCodeCount = 50;  ///< PRNs 1..50

extern const std::array<std::string_view, kE1PrimaryCodeCount> kE1bPrimaryHex;
extern const std::array<std::string_view, kE1PrimaryCodeCount> kE1cPrimaryHex;

}  // namespace deepnav::galileo::detail
