#pragma once
// Random generators of the error world. Each error source, each satellite and each
// component within a source has its own generator seeded from (scenario seed, source, PRN,
// stream), so its values do not change when another source, the satellite selection or
// the run's length changes.
#include <cstdint>
#include <random>

namespace deepnav {

enum class ErrorSource : std::uint32_t { ionosphere = 1, troposphere = 2, orbit_clock = 3 };

inline std::mt19937_64 error_rng(std::uint64_t seed, ErrorSource source, int prn = 0, int stream = 0) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(source), static_cast<std::uint32_t>(prn),
                    static_cast<std::uint32_t>(stream)};
  return std::mt19937_64(seq);
}

}  // namespace deepnav
