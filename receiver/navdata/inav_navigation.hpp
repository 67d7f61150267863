#pragma once
// What one Galileo satellite's I/NAV pages say: its ephemeris (words 1-4 of one IODnav and
// word 5: health, group delays, GST week; signals/galileo/inav_words' EphemerisAssembler),
// the GPS-Galileo time offset (word 10), the GST-UTC parameters (word 6), and GST at the
// start of the pages, so observables can be formed.
//
// Time: words 0 (with time flag 2), 5 and 6 carry the time of week, which refers to the start
// of the page that carries the word (the leading edge of the even part's first sync symbol,
// Galileo OS SIS ICD 5.1.2); words 0 and 5 also carry the GST week, word 6 only the time of
// week (its week is the latest one known, carried over a week boundary). Pages are 2 s, code
// periods 4 ms, so from one time mark the GST of every later code period follows.
#include <cstdint>
#include <optional>
#include <vector>

#include "receiver/navdata/inav_page_decoder.hpp"
#include "receiver/navdata/inav_page_sync.hpp"
#include "receiver/tracking/e1_tracking_types.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/galileo/inav_words.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

/// GST at the start of a page.
struct InavTimeMark {
  double tow_s = 0.0;
  std::optional<int> week;        ///< GST week (12 bits as broadcast) once word 0 or 5 gave one
  std::int64_t first_sample = 0;  ///< the page's first sample (InavPage::first_sample)
  std::int64_t code_period = 0;   ///< its channel code period
};

class InavNavigation {
 public:
  /// `svid`: the satellite the channel tracks; an ephemeris whose word 4 names another one
  /// (a channel caught on another satellite's signal) is withheld. nullopt: not checked.
  explicit InavNavigation(std::optional<int> svid = std::nullopt) : svid_(svid) {}
  /// A CRC-checked page. Words that do not decode (a field out of its range) are counted and
  /// ignored.
  void add(const InavPage& page);

  /// The ephemeris once words 1-4 of one IODnav and a word 5 are in (and of the right SVID).
  std::optional<galileo::GalileoEphemeris> ephemeris() const;
  std::optional<galileo::GgtoParameters> ggto() const { return ggto_; }
  std::optional<UtcParameters> utc() const { return utc_; }
  /// The latest time mark (from the latest word 0, 5 or 6).
  std::optional<InavTimeMark> time_mark() const { return mark_; }
  /// GST time of week at the start of channel code period `code_period` (4 ms each), from the
  /// latest time mark; nullopt before the first one.
  std::optional<double> tow_at_code_period(std::int64_t code_period) const;
  int words() const { return words_; }
  int undecodable_words() const { return undecodable_; }

 private:
  void mark(const InavPage& page, int tow_s, std::optional<int> week);

  std::optional<int> svid_;
  galileo::inav::EphemerisAssembler assembler_;
  std::optional<galileo::GgtoParameters> ggto_;
  std::optional<UtcParameters> utc_;
  std::optional<InavTimeMark> mark_;
  std::optional<int> week_;
  int words_ = 0, undecodable_ = 0;
};

/// The whole chain for one channel: symbols in, page sync, page decoding, navigation.
class InavDecoder {
 public:
  /// `svid` as for InavNavigation.
  explicit InavDecoder(std::optional<int> svid = std::nullopt) : navigation_(svid) {}
  /// One E1-B symbol (consecutive code periods).
  void add(const E1bSymbol& symbol);
  void add(const std::vector<E1bSymbol>& symbols) {
    for (const E1bSymbol& s : symbols) add(s);
  }
  const InavPageSynchronizer& sync() const { return sync_; }
  const InavPageDecoder& pages() const { return pages_; }
  const InavNavigation& navigation() const { return navigation_; }
  /// Pages decoded since the last call, in order.
  std::vector<InavPage> take_pages();

 private:
  InavPageSynchronizer sync_;
  InavPageDecoder pages_;
  InavNavigation navigation_;
  std::vector<InavPagePart> parts_;
  std::vector<InavPage> new_pages_;
};

}  // namespace deepnav
