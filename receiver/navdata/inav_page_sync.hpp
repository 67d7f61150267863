#pragma once
// Page-part synchronisation of a Galileo I/NAV symbol stream (E1-B, 250 symbols/s): every
// page part is the 10-symbol pattern 0101100000 and 240 FEC symbols (signals/galileo/
// inav_page.hpp). Until the channel's carrier phase is tied to the pilot the symbols' sign is
// the Costas loop's guess, so the pattern is searched in either polarity; a match confirmed
// by a second one a part (250 symbols) later fixes the part boundaries and the polarity (both
// exact: one symbol error allowed in each would make a random lock 121 times likelier).
// Locked, each part is handed on with its symbols turned to the true polarity (logic 0
// positive); at the boundaries the pattern may then have one symbol wrong. A pattern seen
// inverted at a part boundary (a half-cycle slip, or the channel's polarity becoming
// absolute) switches the polarity; three boundaries in a row without the pattern, or a break
// in the symbol stream, start the search again.
#include <cstdint>
#include <deque>
#include <vector>

#include "receiver/tracking/e1_tracking_types.hpp"
#include "signals/galileo/inav_fec.hpp"

namespace deepnav {

/// The 240 FEC symbols of one page part, in the true polarity, and where the part began.
struct InavPagePart {
  galileo::inav::PagePartSoftSymbols symbols{};
  std::int64_t first_sample = 0;  ///< sample at which the part's first sync symbol began
  std::int64_t code_period = 0;   ///< channel code period of that symbol
  int polarity = 1;               ///< +1: the stream's signs were right; -1: they were inverted
};

class InavPageSynchronizer {
 public:
  /// One symbol (consecutive code periods); completed parts are appended to `out`.
  void add(const E1bSymbol& symbol, std::vector<InavPagePart>& out);
  bool locked() const { return locked_; }
  int polarity() const { return polarity_; }
  /// Part boundaries where the pattern was missing while locked.
  int missed_patterns() const { return missed_total_; }

 private:
  /// +1 / -1 when the 10 symbols from `index` are the pattern in that polarity with at most
  /// `tolerated` symbols wrong, else 0.
  int pattern_at(std::size_t index, int tolerated) const;
  void unlock();

  std::deque<E1bSymbol> buffer_;
  bool locked_ = false;
  int polarity_ = 1;
  int missed_in_row_ = 0, missed_total_ = 0;
};

}  // namespace deepnav
