#include "receiver/navdata/inav_page_decoder.hpp"

#include "signals/galileo/inav_page.hpp"

namespace deepnav {

std::optional<InavPage> InavPageDecoder::add(const InavPagePart& part) {
  const bool odd = galileo::inav::decode_page_part(part.symbols)[0] != 0;
  if (!odd) {
    if (even_) ++counts_.unpaired_parts;
    even_ = part;
    return std::nullopt;
  }
  const bool follows = even_ && part.code_period == even_->code_period + galileo::inav::kPagePartTotalSymbols;
  if (!follows) {
    ++counts_.unpaired_parts;
    if (even_) ++counts_.unpaired_parts;
    even_.reset();
    return std::nullopt;
  }
  const InavPagePart even = *even_;
  even_.reset();
  const galileo::inav::DecodedPage decoded = galileo::inav::decode_page(even.symbols, part.symbols);
  if (!decoded.crc_ok || !decoded.parts_in_order) {
    ++counts_.crc_failures;
    return std::nullopt;
  }
  if (decoded.page.alert) {
    ++counts_.alert_pages;
    return std::nullopt;
  }
  ++counts_.pages;
  InavPage page;
  page.word = decoded.page.word;
  page.word_type = galileo::inav::word_type(decoded.page.word);
  page.first_sample = even.first_sample;
  page.code_period = even.code_period;
  return page;
}

}  // namespace deepnav
