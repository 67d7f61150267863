#pragma once
// Constants of the Galileo E1 Open Service signal and of the Galileo OS SIS ICD's orbit model
// (Issue 2.0: sections 2.3, 3.4, 5.1.1, 5.1.4).
#include "signals/gps_constants.hpp"

namespace deepnav::galileo {

inline constexpr double kE1_Hz = gps::kL1_Hz;  ///< E1 shares GPS L1's carrier, 1575.42 MHz
inline constexpr double kE1Wavelength_m = gps::kSpeedOfLight_mps / kE1_Hz;
inline constexpr double kE1CodeRate_cps = 1.023e6;
inline constexpr int kE1CodeLength_chips = 4092;
inline constexpr double kE1CodePeriod_s = 4e-3;
/// E1-B carries one I/NAV symbol per primary code period: 250 symbols/s.
inline constexpr double kE1bSymbolRate_sps = 250.0;
inline constexpr int kE1cSecondaryLength_chips = 25;  ///< CS25: one chip per primary code period, 100 ms
inline constexpr int kMaxPrn = 50;                    ///< primary codes exist for PRNs 1..50

// The orbit model's values (ICD Table 64 and 5.1.4), which differ from IS-GPS-200's in GM.
inline constexpr double kGM_m3ps2 = 3.986004418e14;
inline constexpr double kEarthRate_radps = 7.2921151467e-5;
inline constexpr double kRelativisticF = -4.442807309e-10;  ///< -2 sqrt(GM) / c^2, s / sqrt(m)
inline constexpr double kPi = 3.1415926535898;              ///< the value the ICD specifies

/// GST week 0 starts with GPS week 1024 (GST's start epoch, 1999-08-22 00:00 UTC less 13 s,
/// is the GPS week 1024 start): GST week = GPS week - 1024 up to the GGTO of some ns.
inline constexpr int kGstWeekOffsetFromGps = 1024;

}  // namespace deepnav::galileo
