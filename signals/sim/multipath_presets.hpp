#pragma once
// Multipath settings for named receiving environments, so that a scenario (or an
// `errors: {preset: ...}` section) can ask for "urban" without spelling out the channel.
//
//   none      no multipath (MultipathSpec{}).
//   open-sky  ground: antenna 1.5 m above dry soil, |Gamma| = 0.3, -20 dB rejection of
//             arrivals from below the horizon: one echo at 0.03 of the direct amplitude
//             (-30 dB), delay 3 sin(el) m.
//   suburban  land-mobile: 3 Rayleigh taps, -12 dB in all, mean excess delay 20 m,
//             reflectors change every 5 s; blocked 10 % of the time at 30 deg elevation
//             (20 % at the horizon), blocked periods 1.5 s on average, 15 dB attenuation.
//   urban     land-mobile: 5 Rayleigh taps, -6 dB in all, mean excess delay 50 m,
//             reflectors change every 3 s; blocked 35 % of the time at 30 deg (70 % at the
//             horizon), blocked periods 3 s on average, 25 dB attenuation (NLOS only).
// The land-mobile figures follow the ranges Lutz et al. (1991) and the DLR urban channel
// measurements (Steingass & Lehner 2004) report for L band: Rician K around 10 dB in the
// good state for suburban roads, lower in cities; shadowing time shares of 0.1-0.3 on
// suburban roads and 0.3-0.8 in cities at low to medium elevations; echo delays of tens
// to a few hundred nanoseconds.
#include <string>
#include <string_view>
#include <vector>

#include "signals/sim/multipath_spec.hpp"

namespace deepnav {

/// The multipath settings of an environment: none, open-sky, suburban or urban. Throws
/// std::invalid_argument naming the choices for anything else.
MultipathSpec multipath_for_environment(std::string_view environment);
/// The environment names multipath_for_environment() accepts, in order of severity.
std::vector<std::string> multipath_environments();

}  // namespace deepnav
