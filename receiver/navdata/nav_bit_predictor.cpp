#include "receiver/navdata/nav_bit_predictor.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "signals/lnav_parity.hpp"

namespace deepnav {
namespace {

constexpr int kHeaderWords = 2;
constexpr int kPreambleBits = 8;

std::int64_t bit_of_week(std::int64_t bit) {
  return ((bit % lnav::kBitsPerWeek) + lnav::kBitsPerWeek) % lnav::kBitsPerWeek;
}

std::int64_t subframe_in_week(std::int64_t subframe) {
  return ((subframe % lnav::kTowCountsPerWeek) + lnav::kTowCountsPerWeek) % lnav::kTowCountsPerWeek;
}

int segment_of_subframe(std::int64_t k) {
  return NavBitPredictor::body_segment(lnav::subframe_id_at(k), lnav::page_at(k));
}

std::int64_t week_of_subframe(std::int64_t subframe) {
  return (subframe - subframe_in_week(subframe)) / lnav::kTowCountsPerWeek;
}

/// Word 3 of subframe 1 (24 data bits) with its 10-bit WN set to `week` modulo 1024.
std::uint32_t with_week_number(std::uint32_t word3_data, std::int64_t week) {
  constexpr int kWnShift = 14;
  const auto wn = static_cast<std::uint32_t>(((week % 1024) + 1024) % 1024);
  return (wn << kWnShift) | (word3_data & ((1u << kWnShift) - 1u));
}

std::uint8_t chain_bits(bool d29, bool d30) { return static_cast<std::uint8_t>((d29 ? 2u : 0u) | (d30 ? 1u : 0u)); }

int preamble_sign(int bit_in_subframe) {
  return ((lnav::kPreamble >> (kPreambleBits - 1 - bit_in_subframe)) & 1u) ? -1 : 1;
}

}  // namespace

std::int64_t nav_bit_index(const GpsTime& t) {
  return std::int64_t{t.week} * lnav::kBitsPerWeek + static_cast<std::int64_t>(std::floor(t.sow * 50.0));
}

double nav_bit_error_rate(double cn0_dbhz, double integration_s) {
  const double cn0_hz = std::pow(10.0, cn0_dbhz / 10.0);
  return 0.5 * std::erfc(std::sqrt(cn0_hz * integration_s));
}

int NavBitPredictor::body_segment(int subframe_id, int page) {
  if (subframe_id >= 1 && subframe_id <= 3) return subframe_id;
  if ((subframe_id == 4 || subframe_id == 5) && page >= 1 && page <= lnav::kPagesPerCycle) {
    return 4 + (subframe_id - 4) * lnav::kPagesPerCycle + (page - 1);
  }
  throw std::invalid_argument(fmt::format("LNAV body: subframe {} page {} does not exist", subframe_id, page));
}

int NavBitPredictor::segment_of_bit(std::int64_t bit) {
  const std::int64_t b = bit_of_week(bit);
  if (b % lnav::kBitsPerSubframe < kHeaderWords * lnav::kBitsPerWord) return kHeaderSegment;
  return segment_of_subframe(b / lnav::kBitsPerSubframe);
}

void NavBitPredictor::learn(const lnav::DecodedSubframe& sf) {
  const auto& th = sf.tlm_how;
  header_.tlm_message = th.tlm_message;
  header_.integrity_flag = th.integrity_flag;
  header_.tlm_reserved = th.tlm_reserved;
  header_.alert = th.alert;
  header_.anti_spoof = th.anti_spoof;
  tlm_known_ = how_known_ = true;

  const int segment = body_segment(th.subframe_id, sf.page);
  Body fresh;
  for (int i = 0; i < 8; ++i)
    fresh.data[static_cast<std::size_t>(i)] = sf.data[static_cast<std::size_t>(i + kHeaderWords)] & lnav::kDataMask;
  set_chain(fresh, lnav::encode_words(sf.data));
  fresh.known = 0xFF;
  fresh.source = Source::broadcast;
  Body& body = bodies_[static_cast<std::size_t>(segment)];
  if (is_ephemeris_segment(segment)) {
    // A new data set, not the week number rolling over: subframe 1's WN is no part of it,
    // nor are word 10's last two bits (set for its parity, which a new WN changes).
    const auto comparable = [&](const Body& b, int i) {
      const std::uint32_t data = b.data[static_cast<std::size_t>(i)];
      if (segment == 1 && i == 0) return with_week_number(data, 0);
      return i == 7 ? data & ~3u : data;
    };
    bool differs = false;
    for (int i = 0; i < 8; ++i)
      differs = differs || ((body.known >> i & 1u) && comparable(body, i) != comparable(fresh, i));
    if (differs) {
      if (body.source == Source::broadcast) ++uploads_;
      for (int other = 1; other <= 3; ++other) {
        if (other != segment) bodies_[static_cast<std::size_t>(other)] = Body{};
      }
    }
  }
  body = fresh;
  changed();
}

void NavBitPredictor::set_chain(Body& body, const lnav::Subframe& words) {
  for (int w = kHeaderWords; w < 10; ++w) {
    const std::uint32_t prev = words[static_cast<std::size_t>(w - 1)];
    body.chain[static_cast<std::size_t>(w - kHeaderWords)] = chain_bits(lnav::word_d29(prev), lnav::word_d30(prev));
  }
}

bool NavBitPredictor::learn_word(std::int64_t subframe_of_week, int word, std::uint32_t data24, bool prev_d29,
                                 bool prev_d30) {
  const std::int64_t k = subframe_in_week(subframe_of_week);
  data24 &= lnav::kDataMask;
  if (word < 0 || word > 9) throw std::invalid_argument(fmt::format("LNAV word index {} is not in 0..9", word));
  if (word == 0) {
    if ((data24 >> 16) != lnav::kPreamble) return false;
    const lnav::TlmHow th = lnav::tlm_how_from_data(data24, 0);
    header_.tlm_message = th.tlm_message;
    header_.integrity_flag = th.integrity_flag;
    header_.tlm_reserved = th.tlm_reserved;
    tlm_known_ = true;
  } else if (word == 1) {
    const lnav::TlmHow th = lnav::tlm_how_from_data(0, data24);
    if (th.tow_count != (k + 1) % lnav::kTowCountsPerWeek || th.subframe_id != lnav::subframe_id_at(k)) {
      ++how_mismatches_;
      return false;
    }
    header_.alert = th.alert;
    header_.anti_spoof = th.anti_spoof;
    how_known_ = true;
  } else {
    Body& body = bodies_[static_cast<std::size_t>(segment_of_subframe(k))];
    body.data[static_cast<std::size_t>(word - kHeaderWords)] = data24;
    body.chain[static_cast<std::size_t>(word - kHeaderWords)] =
        word == kHeaderWords ? 0 : chain_bits(prev_d29, prev_d30);
    body.known = static_cast<std::uint8_t>(body.known | (1u << (word - kHeaderWords)));
    body.source = Source::broadcast;
  }
  changed();
  return true;
}

void NavBitPredictor::assist(const Ephemeris& eph, const std::optional<lnav::TlmHow>& header) {
  lnav::LnavContent content;
  content.eph = eph;
  for (int id = 1; id <= 3; ++id) {
    Body& body = bodies_[static_cast<std::size_t>(id)];
    if (body.source == Source::broadcast && body.known != 0) continue;
    const lnav::Subframe words = lnav::encode_subframe(id, content, 1, 1);
    const auto decoded = lnav::decode_subframe(words);
    if (!decoded) throw std::logic_error("LNAV: an encoded subframe failed its own parity");
    for (int i = 0; i < 8; ++i)
      body.data[static_cast<std::size_t>(i)] = decoded->data[static_cast<std::size_t>(i + kHeaderWords)];
    set_chain(body, words);
    body.known = 0xFF;
    body.source = Source::assisted;
  }
  if (header) {
    if (!tlm_known_) {
      header_.tlm_message = header->tlm_message;
      header_.integrity_flag = header->integrity_flag;
      header_.tlm_reserved = header->tlm_reserved;
      tlm_known_ = true;
    }
    if (!how_known_) {
      header_.alert = header->alert;
      header_.anti_spoof = header->anti_spoof;
      how_known_ = true;
    }
  }
  changed();
}

void NavBitPredictor::forget(int segment) {
  if (segment < 0 || segment >= kSegments)
    throw std::invalid_argument(fmt::format("LNAV segment {} is not in 0..53", segment));
  if (segment == kHeaderSegment) {
    tlm_known_ = how_known_ = false;
  } else {
    bodies_[static_cast<std::size_t>(segment)] = Body{};
  }
  changed();
}

void NavBitPredictor::forget_after_failure(int segment) {
  if (is_ephemeris_segment(segment)) {
    for (int s = 1; s <= 3; ++s) forget(s);
  } else {
    forget(segment);
  }
}

const NavBitPredictor::Predicted& NavBitPredictor::predicted(std::int64_t subframe) const {
  if (cache_.subframe == subframe && cache_.version == version_) return cache_;
  const std::int64_t k = subframe_in_week(subframe);
  const int id = lnav::subframe_id_at(k);
  const Body& body = bodies_[static_cast<std::size_t>(segment_of_subframe(k))];
  lnav::TlmHow th = header_;
  th.tow_count = static_cast<int>((k + 1) % lnav::kTowCountsPerWeek);
  th.subframe_id = id;
  const auto tlm_how = lnav::tlm_how_data(th);
  // Word by word as the satellite encodes them (lnav::encode_words), each with the D29*, D30*
  // of the word before: predicted, fixed at 0 after a HOW or word 10, or as last received.
  std::uint16_t known = 0;
  bool d29 = false, d30 = false, chain_known = true;
  for (int w = 0; w < 10; ++w) {
    bool data_known = false;
    std::uint32_t data = 0;
    if (w < kHeaderWords) {
      data_known = w == 0 ? tlm_known_ : how_known_;
      data = tlm_how[static_cast<std::size_t>(w)];
    } else {
      const auto i = static_cast<std::size_t>(w - kHeaderWords);
      data_known = (body.known >> i) & 1u;
      data = body.data[i];
      // Subframe 1's WN (the 10 MSBs of word 3) is the week the subframe is sent in: it
      // rolls over at the week boundary, whenever the rest of the body was learned.
      if (id == 1 && w == kHeaderWords) data = with_week_number(data, week_of_subframe(subframe));
      if (w == kHeaderWords) {
        d29 = d30 = false;
        chain_known = true;
      } else if (!chain_known && data_known) {
        d29 = (body.chain[i] >> 1) & 1u;
        d30 = body.chain[i] & 1u;
        chain_known = true;
      }
    }
    if (!data_known || !chain_known) {
      chain_known = false;
      continue;
    }
    if (w == 1 || w == 9) data = lnav::with_noninformation_bits(data, d29, d30);
    const std::uint32_t word = lnav::encode_word(data, d29, d30);
    cache_.words[static_cast<std::size_t>(w)] = word;
    known = static_cast<std::uint16_t>(known | (1u << w));
    d29 = lnav::word_d29(word);
    d30 = lnav::word_d30(word);
  }
  cache_.known = known;
  cache_.subframe = subframe;
  cache_.version = version_;
  return cache_;
}

int NavBitPredictor::sign(std::int64_t bit) const {
  const std::int64_t b = bit_of_week(bit);
  const auto& p = predicted((bit - b) / lnav::kBitsPerSubframe + b / lnav::kBitsPerSubframe);
  const int i = static_cast<int>(b % lnav::kBitsPerSubframe);
  if ((p.known >> (i / lnav::kBitsPerWord)) & 1u) return lnav::subframe_bit(p.words, i) ? -1 : 1;
  return i < kPreambleBits ? preamble_sign(i) : 0;
}

void NavBitPredictor::signs(std::int64_t first_bit, std::span<std::int8_t> out) const {
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = static_cast<std::int8_t>(sign(first_bit + static_cast<std::int64_t>(i)));
}

bool NavBitPredictor::word_data_known(std::int64_t subframe_of_week, int word) const {
  if (word == 0) return tlm_known_;
  if (word == 1) return how_known_;
  const Body& body = bodies_[static_cast<std::size_t>(segment_of_subframe(subframe_in_week(subframe_of_week)))];
  return (body.known >> (word - kHeaderWords)) & 1u;
}

int NavBitPredictor::body_words_known(int segment) const {
  if (segment <= kHeaderSegment || segment >= kSegments) return 0;
  int n = 0;
  for (int i = 0; i < 8; ++i) n += (bodies_[static_cast<std::size_t>(segment)].known >> i) & 1;
  return n;
}

}  // namespace deepnav
