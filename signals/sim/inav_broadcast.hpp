#pragma once
// The I/NAV message a synthesized Galileo satellite broadcasts on E1-B, and its symbols over a
// span of time: the one definition the IF synthesizer modulates and its tests decode.
//
// Nominal pages of two seconds (even part, odd part), the even part starting at an even GST
// second, in 30 s subframes of 15 pages (Galileo OS SIS ICD 4.3.2, nominal E1-B subframe
// layout), page slot n (GST second mod 30 = 2n) carrying:
//   0: word 2   1: word 4   2: word 6   3: word 7 / 9   4: word 8 / 10   10: word 1
//   11: word 3  12: word 5  the others: word 0 (spare word with GST)
// where words 7 and 8 go in even subframes and 9 and 10 in odd ones (GST second / 30).
// Only word 10 of the almanac words is sent, for its GPS-Galileo time offset (its almanac
// fields are empty: SVID 0); the slots of words 7, 8 and 9 carry the dummy word (type 63).
// Every TOW is the GST second at which its page's even part starts. Odd-part fields
// (OSNMA, SAR, spare, reserved 2) are zero.
#include <cstdint>
#include <vector>

#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/inav_words.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

/// The word a satellite broadcasting `eph` sends in the page that starts at GST second
/// `page_start_s` (even), counted from GST's start epoch; nav supplies the NeQuick G, GST-UTC
/// (with the GPS leap second fields) and GGTO parameters.
galileo::inav::Word synthesized_inav_word(const NavData& nav, const galileo::GalileoEphemeris& eph,
                                          std::int64_t page_start_s);

/// The E1-B symbol signs (+1 for logic 0, -1 for logic 1) over a span, indexed by the absolute
/// 4 ms code period counted from GST's start epoch (250 periods per second: symbol
/// period mod 250 of GST second period / 250).
class InavSymbolTable {
 public:
  /// Covers the whole pages that contain periods first_period .. last_period.
  InavSymbolTable(const NavData& nav, const galileo::GalileoEphemeris& eph, std::int64_t first_period,
                  std::int64_t last_period);
  /// Sign of the symbol of period `period`; std::logic_error outside the span.
  int sign_at_period(std::int64_t period) const;

 private:
  std::int64_t first_period_ = 0;
  std::vector<std::int8_t> signs_;
};

}  // namespace deepnav
