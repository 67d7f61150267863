#pragma once
// The LNAV message a synthesized satellite broadcasts, and its data-bit signs over a span of
// time: the one definition the IF synthesizer modulates and the tests of the receiver's
// navigation-bit prediction compare against.
#include <cstdint>
#include <vector>

#include "signals/lnav_message.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

/// What a synthesized satellite broadcasts with ephemeris `eph`: that ephemeris in subframes
/// 1-3, the navigation file's ionosphere and UTC parameters, and almanac pages derived from
/// the first record of every PRN in the file (dummy pages for PRNs the file lacks). TLM
/// message, flags and A-S/configuration words are zero. The week of transmission is left
/// to LnavSignTable, which knows when each subframe is sent.
lnav::LnavContent synthesized_lnav_content(const NavData& nav, const Ephemeris& eph);

/// The LNAV data-bit signs (+1 for bit 0, -1 for bit 1) a satellite transmits over a span of
/// its own time, indexed by the absolute 1 ms code period counted from the GPS time origin
/// (20 periods per bit; bit b = period / 20 is the absolute bit index, b mod
/// lnav::kBitsPerWeek its bit of the week). Subframe 1's week number is the week each
/// subframe is sent in, so a span across a week boundary broadcasts both weeks.
class LnavSignTable {
 public:
  /// Covers the whole subframes that contain periods first_ms .. last_ms.
  LnavSignTable(const lnav::LnavContent& content, std::int64_t first_ms, std::int64_t last_ms);
  /// Sign of the data bit that modulates code period `ms`; std::logic_error outside the span.
  int sign_at_ms(std::int64_t ms) const;
  /// Sign of absolute data bit `bit`; std::logic_error outside the span.
  int sign_of_bit(std::int64_t bit) const;

 private:
  std::int64_t first_subframe_ = 0;
  std::vector<std::int8_t> signs_;
};

}  // namespace deepnav
