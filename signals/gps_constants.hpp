#pragma once
// Constants of the GPS L1 C/A signal and of IS-GPS-200's orbit model.
namespace deepnav::gps {

inline constexpr double kSpeedOfLight_mps = 299792458.0;
inline constexpr double kL1_Hz = 1575.42e6;
inline constexpr double kL1Wavelength_m = kSpeedOfLight_mps / kL1_Hz;
inline constexpr double kCodeRate_cps = 1.023e6;
inline constexpr int kCodeLength_chips = 1023;
inline constexpr double kCodePeriod_s = 1e-3;
inline constexpr double kBitPeriod_s = 20e-3;
inline constexpr int kCodePeriodsPerBit = 20;
inline constexpr double kChipsPerCycle = kCodeRate_cps / kL1_Hz;  // code/carrier frequency ratio 1/1540

// IS-GPS-200 Table 20-IV values (these, not WGS-84's, go into the orbit equations).
inline constexpr double kGM_m3ps2 = 3.986005e14;
inline constexpr double kEarthRate_radps = 7.2921151467e-5;
inline constexpr double kRelativisticF = -4.442807633e-10;  // s / sqrt(m)
inline constexpr double kPi = 3.1415926535898;              // the value IS-GPS-200 specifies

inline constexpr int kMaxPrn = 32;

}  // namespace deepnav::gps
