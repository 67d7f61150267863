#pragma once
// An I/NAV message for the decoder tests: one satellite's ephemeris (E01's broadcast batch of
// 2022-02-19 22:00, values within rounding of the fields' LSBs, sent here as E11), word 5, word 6, word 10 and
// spare words with the time, encoded into E1-B symbol levels page by page with the signal
// layer's own encoders (signals/galileo/inav_words, inav_page, inav_fec).
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/inav_page.hpp"
#include "signals/galileo/inav_words.hpp"
#include "tests/support/galileo_test_ephemeris.hpp"

namespace deepnav::testing {

namespace inav = galileo::inav;

constexpr int kInavTestSvid = 11;

inline galileo::GalileoEphemeris inav_test_ephemeris() {
  galileo::GalileoEphemeris eph = e01_inav_batch();
  eph.prn = kInavTestSvid;
  return eph;
}

/// GST time of week at the start of the message's first page.
constexpr int kInavTestTow0 = 597590;

/// Word 5 of the message, sent as page `page` (its TOW is that page's start).
inline inav::IonoDelayHealthWord inav_test_word5(int page) {
  inav::IonoDelayHealthWord w;
  w.iono = {81.25, -2.4609375E-01, 3.753662109375E-03, {false, true, false, false, true}, true};
  w.bgd_e1e5a_s = 2.328306436539E-10;
  w.bgd_e1e5b_s = -4.656612873077E-10;
  w.week = 1173;
  w.tow_s = kInavTestTow0 + 2 * page;
  return w;
}

inline UtcParameters inav_test_utc() {
  return {-9.3132257462E-10, 8.881784197E-16, 0, 1173 % 256, 18, 137, 7, 18, true};
}
inline galileo::GgtoParameters inav_test_ggto() { return {5.908e-09, 3.552713679E-15, 86400, 1173 % 64, true}; }

/// The word of I/NAV type `type` (0-6, 10) as page `page` of the message.
inline inav::Word inav_test_word(int type, int page) {
  const galileo::GalileoEphemeris eph = inav_test_ephemeris();
  switch (type) {
    case 0:
      return inav::encode_spare_word({2, 1173, kInavTestTow0 + 2 * page});
    case 5:
      return inav::encode_iono_delay_health_word(inav_test_word5(page));
    case 6:
      return inav::encode_utc_word({inav_test_utc(), kInavTestTow0 + 2 * page});
    case 10: {
      inav::AlmanacBatch batch;
      batch.ggto = inav_test_ggto();
      return inav::encode_almanac_word(10, batch);
    }
    default:
      return inav::encode_ephemeris_word(type, eph);
  }
}

/// Symbol levels (+1 logic 0, -1 logic 1) of pages carrying `types` in order, page k starting
/// at symbol 500 k.
inline std::vector<int> inav_test_symbols(const std::vector<int>& types) {
  std::vector<int> levels;
  for (std::size_t k = 0; k < types.size(); ++k) {
    inav::NominalPage page;
    page.word = inav_test_word(types[k], static_cast<int>(k));
    for (const inav::PagePartTransmission& part : inav::encode_page(page))
      for (std::uint8_t s : part) levels.push_back(s ? -1 : 1);
  }
  return levels;
}

/// The ephemeris the words of the message carry (as the words' fields round them).
inline galileo::GalileoEphemeris inav_test_expected_ephemeris() {
  inav::EphemerisAssembler a;
  for (int type = 1; type <= 5; ++type) a.add(inav_test_word(type, type));
  return *a.ephemeris();
}

}  // namespace deepnav::testing
