#include "receiver/navdata/inav_navigation.hpp"

#include <cmath>
#include <stdexcept>

#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/inav_page.hpp"

namespace deepnav {
namespace {

namespace inav = galileo::inav;
constexpr int kSpareTimeValid = 2;  // word 0's time flag: binary 10, week and TOW valid
constexpr int kWeekModulo = 4096;   // the I/NAV week field has 12 bits

}  // namespace

void InavNavigation::mark(const InavPage& page, int tow_s, std::optional<int> week) {
  if (week) {
    week_ = week;
  } else if (week_ && mark_ && tow_s < mark_->tow_s) {
    week_ = (*week_ + 1) % kWeekModulo;  // word 6 after the week turned
  }
  mark_ = InavTimeMark{static_cast<double>(tow_s), week_, page.first_sample, page.code_period};
}

void InavNavigation::add(const InavPage& page) {
  ++words_;
  try {
    switch (page.word_type) {
      case 0: {
        const inav::SpareWord w = inav::decode_spare_word(page.word);
        if (w.time_flag == kSpareTimeValid) mark(page, w.tow_s, w.week);
        break;
      }
      case 1:
      case 2:
      case 3:
      case 4:
        assembler_.add(page.word);
        break;
      case 5: {
        assembler_.add(page.word);
        const inav::IonoDelayHealthWord w = inav::decode_iono_delay_health_word(page.word);
        mark(page, w.tow_s, w.week);
        break;
      }
      case 6: {
        const inav::UtcWord w = inav::decode_utc_word(page.word);
        utc_ = w.utc;
        mark(page, w.tow_s, std::nullopt);
        break;
      }
      case 10: {
        inav::AlmanacBatch batch;
        inav::decode_almanac_word(page.word, batch);
        ggto_ = batch.ggto;
        break;
      }
      default:
        break;  // almanacs 7-9, dummy and reserved words are not used here
    }
  } catch (const std::invalid_argument&) {
    ++undecodable_;
  }
}

std::optional<galileo::GalileoEphemeris> InavNavigation::ephemeris() const {
  auto eph = assembler_.ephemeris();
  if (eph && svid_ && eph->prn != *svid_) return std::nullopt;
  return eph;
}

std::optional<double> InavNavigation::tow_at_code_period(std::int64_t code_period) const {
  if (!mark_) return std::nullopt;
  const double tow = mark_->tow_s + static_cast<double>(code_period - mark_->code_period) * galileo::kE1CodePeriod_s;
  const double week_s = 604800.0;
  return tow - week_s * std::floor(tow / week_s);
}

void InavDecoder::add(const E1bSymbol& symbol) {
  parts_.clear();
  sync_.add(symbol, parts_);
  for (const InavPagePart& part : parts_) {
    if (auto page = pages_.add(part)) {
      navigation_.add(*page);
      new_pages_.push_back(*page);
    }
  }
}

std::vector<InavPage> InavDecoder::take_pages() {
  std::vector<InavPage> out;
  out.swap(new_pages_);
  return out;
}

}  // namespace deepnav
