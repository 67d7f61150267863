#pragma once
// Galileo I/NAV nominal pages from synchronised page parts: each part is Viterbi-decoded
// (signals/galileo/inav_fec) to read its even/odd bit, an even part followed directly by an
// odd one forms a page, and the page's CRC-24Q (over both parts' 196 bits) decides whether
// its 128-bit word is used. Pages that fail the CRC are counted and dropped; so are alert
// pages (page type 1: their word is not to be used for navigation) and parts without a
// partner.
#include <cstdint>
#include <optional>

#include "receiver/navdata/inav_page_sync.hpp"
#include "signals/galileo/inav_words.hpp"

namespace deepnav {

/// A page whose CRC matched.
struct InavPage {
  galileo::inav::Word word{};
  int word_type = 0;
  std::int64_t first_sample = 0;  ///< the even part's first sync symbol: the page's start
  std::int64_t code_period = 0;   ///< channel code period of that symbol
};

struct InavPageCounts {
  int pages = 0;           ///< CRC-checked pages handed on
  int crc_failures = 0;    ///< paired parts whose CRC did not match: dropped
  int alert_pages = 0;     ///< CRC-checked alert pages: dropped
  int unpaired_parts = 0;  ///< an odd part without its even part, or an even part left alone
};

class InavPageDecoder {
 public:
  /// The next synchronised part; the page once an odd part completes a good one.
  std::optional<InavPage> add(const InavPagePart& part);
  const InavPageCounts& counts() const { return counts_; }

 private:
  std::optional<InavPagePart> even_;
  InavPageCounts counts_;
};

}  // namespace deepnav
